// Two pieces of work at once: the tree's build (bvh_build.h, bvh.h) on two threads.
#pragma once

#include <exception>
#include <thread>

namespace rt {

// Runs other() on a new thread while here() runs on this one, and returns when both
// are done; an exception of either (out of memory) is rethrown here after both.
template <typename Other, typename Here>
void run_beside(Other other, Here here) {
    std::exception_ptr failure;
    std::thread thread([&] {
        try {
            other();
        } catch (...) {
            failure = std::current_exception();
        }
    });
    try {
        here();
    } catch (...) {
        thread.join();
        throw;
    }
    thread.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace rt
