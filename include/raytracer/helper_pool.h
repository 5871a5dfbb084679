// The renderer's helper threads: made once per process, started on idle cores, and
// never waited for when they come too late to help.
#pragma once

#include <type_traits>

namespace rt {

// The cores this process may run on: its CPU affinity mask on Linux (which taskset and
// container cpusets narrow), std::thread::hardware_concurrency() elsewhere; at least 1.
unsigned available_cores();

// The threads a render is asked for: `threads`, or available_cores() where it is 0.
inline unsigned threads_asked(unsigned threads) { return threads == 0 ? available_cores() : threads; }

// One job at a time for a process-wide set of helper threads:
//
//   HelperPool::Job job;                             // closes the job when destroyed
//   unsigned n = job.start(helpers, body, context);  // body(context, h), h < n, on helpers
//   ...the caller works too...
//   job.finish();  // returns once no helper is inside body, and none enters it after
//
// WHY a pool rather than a std::thread per render:
// - Linux starts a new thread on its creator's CPU, and the idle core takes it over
//   only at a later load balance: 2 to 3 ms in this virtual machine while the creator
//   keeps its CPU busy, longer than a whole 400x400 render. Created with an affinity
//   mask that leaves out the creator's CPU, a thread is queued on an idle core at once
//   (measured: running 0.05 to 0.15 ms after pthread_create returns); it then widens
//   its mask again, so that the scheduler may still move it later.
// - Joining a thread waits for its exit, 0.05 to 0.08 ms after its last row here, and
//   for a helper that has not run yet (its core busy), however long that takes.
//   finish() waits only for helpers inside body; a helper that comes later finds the
//   job closed and goes back to sleep. The threads sleep until retire() or the end of
//   the process.
//
// start() returns 0 (the caller does the whole job) when another job is running, so
// that renders on several threads at once stay correct, or when no thread can be made.
// body must not throw.
class HelperPool {
public:
    using Body = void (*)(void* context, unsigned helper);

    class Job {
    public:
        Job() = default;
        Job(const Job&) = delete;
        Job& operator=(const Job&) = delete;
        ~Job() { finish(); }

        unsigned start(unsigned helpers, Body body, void* context);
        // The same with work() or work(helper) as the body (work outlives the job).
        template <typename Work>
        unsigned start(unsigned helpers, Work& work) {
            return start(
                helpers,
                [](void* context, unsigned helper) {
                    Work& w = *static_cast<Work*>(context);
                    if constexpr (std::is_invocable_v<Work&, unsigned>)
                        w(helper);
                    else
                        w();
                },
                &work);
        }
        void finish();

    private:
        bool started_ = false;
    };

    // Ends the helpers: each sleeping one wakes and exits, on its own core, and jobs
    // started from now on get none (start() returns 0). For a program about to end:
    // WHY: a helper still asleep when the process exits is woken by the exit to be
    // ended, and the exit waits for it (about 0.06 ms more here, in the median, where the
    // core it sleeps on has gone idle); woken now, it is gone while the caller writes and
    // closes its file.
    static void retire();

    // True where a new helper starts on another core at once (Linux): a helper then
    // pays on far shorter renders.
    static bool starts_on_idle_core();
};

}  // namespace rt
