// Two pieces of work at once: the tree's build (bvh_build.h, bvh.h) on two threads.
#pragma once

#include <atomic>
#include <exception>

#include "raytracer/helper_pool.h"

namespace rt {

// Runs other() on a helper of the process's pool (helper_pool.h: no thread to start,
// and one that starts on an idle core) while here() runs on this one, and returns when
// both are done. Where no helper takes other() by the time here() is done, this thread
// runs it. An exception of either (out of memory) is rethrown here after both.
template <typename Other, typename Here>
void run_beside(Other other, Here here) {
    struct Shared {
        explicit Shared(Other& work) : other(work) {}
        Other& other;
        std::atomic<bool> taken{false};
        std::exception_ptr failure;

        void claim() {  // other(), by whichever thread comes first
            if (taken.exchange(true)) return;
            try {
                other();
            } catch (...) {
                failure = std::current_exception();
            }
        }
    } shared(other);
    auto claim = [&shared] { shared.claim(); };
    HelperPool::Job job;  // declared after what the helper uses: closed first
    job.start(1, claim);
    here();  // on an exception, ~Job() waits for a helper inside other()
    shared.claim();
    job.finish();
    if (shared.failure) std::rethrow_exception(shared.failure);
}

}  // namespace rt
