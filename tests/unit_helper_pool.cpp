// The helper pool's promises (helper_pool.h): every helper a job asks for may take
// part; none is inside the job's body once finish() returns, and none enters it after;
// one job at a time; the pool is reused by later jobs of any size; retire() ends it.
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <thread>
#include <vector>

#ifndef _WIN32
#include <pthread.h>
#endif

#include "check.h"
#include "raytracer/compiler.h"
#include "raytracer/helper_pool.h"

namespace {

// What a job's body records: each helper's calls, and whether any call came while the
// test considered the job over.
struct Record {
    std::atomic<bool> over{false};
    std::atomic<int> late_calls{0};
    std::atomic<int> inside{0};
    std::vector<std::atomic<int>> calls;
    std::atomic<int> work{0};  // units of a shared counter, as rows are shared in render()
    int units = 0;
    explicit Record(unsigned helpers, int units_) : calls(helpers), units(units_) {}
};

void body(void* context, unsigned helper) {
    Record& r = *static_cast<Record*>(context);
    if (r.over.load()) ++r.late_calls;
    ++r.inside;
    ++r.calls[helper];
    while (r.work++ < r.units) std::this_thread::yield();
    --r.inside;
}

}  // namespace

TEST(available_cores_is_at_least_one) { CHECK(rt::available_cores() >= 1); }

TEST(helpers_take_part_and_are_out_when_finish_returns) {
    for (unsigned helpers : {1U, 3U, 7U}) {
        Record r(helpers, 200000);
        rt::HelperPool::Job job;
        const unsigned started = job.start(helpers, body, &r);
        CHECK_EQ(started, helpers);
        // The caller shares the work, as render() does.
        while (r.work++ < r.units) std::this_thread::yield();
        job.finish();
        CHECK_EQ(r.inside.load(), 0);
        r.over = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        CHECK_EQ(r.late_calls.load(), 0);
        for (unsigned h = 0; h < helpers; ++h) CHECK(r.calls[h].load() <= 1);
    }
}

// Jobs closed at once, before most helpers wake: a helper that comes late must find the
// job closed, and never enter a later job twice or with the wrong helper number.
TEST(late_helpers_never_enter_a_finished_job) {
    for (int round = 0; round < 2000; ++round) {
        const unsigned helpers = 1 + static_cast<unsigned>(round % 4);
        Record r(helpers, round % 3 == 0 ? 1000 : 0);
        {
            rt::HelperPool::Job job;  // its destructor finishes
            job.start(helpers, body, &r);
            while (r.work++ < r.units) {
            }
        }
        CHECK_EQ(r.inside.load(), 0);
        r.over = true;
        // Time for the helpers woken for this job to come, before the next one opens.
        const auto until =
            std::chrono::steady_clock::now() + std::chrono::microseconds(round % 2 == 0 ? 30 : 0);
        while (std::chrono::steady_clock::now() < until) std::this_thread::yield();
        for (unsigned h = 0; h < helpers; ++h) CHECK(r.calls[h].load() <= 1);
        CHECK_EQ(r.late_calls.load(), 0);
    }
}

TEST(one_job_at_a_time) {
    Record first(1, 0), second(1, 0);
    rt::HelperPool::Job a;
    CHECK_EQ(a.start(1, body, &first), 1U);
    std::atomic<unsigned> got{99};
    // From another thread, as a second render would be: no helpers while a runs.
    std::thread other([&] {
        rt::HelperPool::Job b;
        got = b.start(1, body, &second);
    });
    other.join();
    CHECK_EQ(got.load(), 0U);
    a.finish();
    rt::HelperPool::Job c;
    CHECK_EQ(c.start(1, body, &second), 1U);  // free again
    c.finish();
    CHECK_EQ(c.start(0, body, &second), 0U);  // nothing asked, nothing started
}

#ifndef _WIN32
// The helpers never take an interrupt (interrupts.h): its handler runs on the thread that
// draws the progress line. The starting thread's own mask is as it was.
TEST(helpers_start_with_the_interrupts_blocked) {
    struct Masks {
        std::atomic<int> blocked{0}, calls{0};
    } masks;
    auto record = [](void* context, unsigned) {
        Masks& m = *static_cast<Masks*>(context);
        sigset_t now;
        CHECK_EQ(pthread_sigmask(SIG_BLOCK, nullptr, &now), 0);
        if (sigismember(&now, SIGINT) == 1 && sigismember(&now, SIGTERM) == 1 &&
            sigismember(&now, SIGHUP) == 1)
            ++m.blocked;
        ++m.calls;
    };
    sigset_t before;
    CHECK_EQ(pthread_sigmask(SIG_BLOCK, nullptr, &before), 0);
    rt::HelperPool::Job job;
    const unsigned started = job.start(5, record, &masks);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (masks.calls.load() < static_cast<int>(started) && std::chrono::steady_clock::now() < until)
        std::this_thread::yield();
    job.finish();
    CHECK(started >= 1U);
    CHECK_EQ(masks.calls.load(), static_cast<int>(started));
    CHECK_EQ(masks.blocked.load(), masks.calls.load());
    sigset_t after;
    CHECK_EQ(pthread_sigmask(SIG_BLOCK, nullptr, &after), 0);
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) CHECK_EQ(sigismember(&after, s), sigismember(&before, s));
}
#endif

// Last in this file: retire() is for the rest of the process.
TEST(retired_helpers_end_and_later_jobs_run_alone) {
    Record r(3, 1000);
    {
        rt::HelperPool::Job job;
        CHECK_EQ(job.start(3, body, &r), 3U);
        while (r.work++ < r.units) std::this_thread::yield();
    }
    rt::HelperPool::retire();
#if defined(__linux__) && !defined(RT_UNDER_TSAN)
    // Each helper wakes and exits: the process is back to its one thread (where /proc is
    // mounted; ThreadSanitizer keeps a thread of its own).
    const std::filesystem::path tasks = "/proc/self/task";
    if (std::filesystem::exists(tasks)) {
        auto threads = [&tasks] {
            int count = 0;
            for (const auto& entry : std::filesystem::directory_iterator(tasks))
                count += !entry.path().empty();
            return count;
        };
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (threads() > 1 && std::chrono::steady_clock::now() < until)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        CHECK_EQ(threads(), 1);
    }
#endif
    Record later(2, 0);
    rt::HelperPool::Job job;
    CHECK_EQ(job.start(2, body, &later), 0U);  // the caller does it all
    job.finish();
    CHECK_EQ(later.calls[0].load() + later.calls[1].load(), 0);
}
