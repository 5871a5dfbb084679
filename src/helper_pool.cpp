#include "raytracer/helper_pool.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <mutex>
#include <system_error>
#include <thread>

#include "raytracer/interrupts.h"

// Linux with glibc: pthreads with an affinity attribute. Everything else, MinGW and
// MSVC included: std::thread, started wherever the system puts it.
#if defined(__linux__) && defined(__GLIBC__)
#define RT_HELPERS_PINNED_START 1
#include <sched.h>
#else
#define RT_HELPERS_PINNED_START 0
#endif
#ifndef _WIN32
#include <pthread.h>
#endif

namespace rt {
namespace {

struct Pool {
    std::mutex job_mutex;  // held from start() to finish(): one job at a time
    // The job: (id << 1) | open, one word so that a helper reads both at once. Ids
    // start at 1; a helper remembers the last id it has seen.
    std::atomic<std::uint64_t> state{0};
    std::atomic<unsigned> inside{0};  // helpers inside body
    // Written by start() before the job opens, read by helpers only while open and
    // inside, and finish() waits for inside = 0 before another start(): never raced.
    HelperPool::Body body = nullptr;
    void* context = nullptr;
    unsigned helpers = 0;
    unsigned threads = 0;               // made so far (under job_mutex)
    std::atomic<unsigned> numbered{0};  // each new helper takes the next number
    std::mutex wake_mutex;
    std::condition_variable wake;
    bool retired = false;  // under wake_mutex: the helpers end (retire())
    // finish() sleeping until inside is 0; the helper leaving last wakes it.
    std::atomic<bool> finisher_asleep{false};
    std::condition_variable all_left;  // with wake_mutex
#if RT_HELPERS_PINNED_START
    cpu_set_t process_cpus;
    bool have_process_cpus = false;
#endif
};

// How long finish() yields before it sleeps: about as long as a helper takes to wake
// (0.05-0.15 ms here). Counted: 112 of 120 course renders at 400x400 ended within it; the
// halves of a tree's build mostly do not (random 100k: 4 of 5 slept).
constexpr std::chrono::microseconds kYieldBeforeSleep{200};

// Never destroyed: sleeping helpers wait on it until retire() or the end of the process.
Pool& pool() {
    static Pool* const p = new Pool;
    return *p;
}

void serve(unsigned index) {
    Pool& p = pool();
    std::uint64_t seen = 0;  // the id of the last job this helper has seen
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(p.wake_mutex);
            p.wake.wait(lock, [&] { return p.retired || (p.state.load() >> 1) != seen; });
            if (p.retired) return;
        }
        // Entering before reading the state pairs with finish(), which closes before
        // reading inside (both sequentially consistent): either finish() sees this
        // helper inside and waits, or this helper sees the job closed.
        p.inside.fetch_add(1);
        const std::uint64_t state = p.state.load();
        if ((state & 1U) != 0 && index < p.helpers) p.body(p.context, index);
        seen = state >> 1;
        // Leaving before reading finisher_asleep pairs with finish(), which raises it
        // before reading inside: either finish() sees no helper inside, or this one
        // sees it asleep and wakes it (under the mutex, so not before it sleeps).
        if (p.inside.fetch_sub(1) == 1 && p.finisher_asleep.load()) {
            const std::lock_guard<std::mutex> lock(p.wake_mutex);
            p.all_left.notify_all();
        }
    }
}

#if RT_HELPERS_PINNED_START
void* serve_pinned(void* /*unused*/) {
    Pool& p = pool();
    // Made on another CPU than its creator's; from now on anywhere the process may run.
    sched_setaffinity(0, sizeof p.process_cpus, &p.process_cpus);
    serve(p.numbered++);
    return nullptr;
}

bool make_helper(Pool& p) {
    pthread_attr_t attr;
    if (pthread_attr_init(&attr) != 0) return false;
    if (p.have_process_cpus) {
        cpu_set_t others = p.process_cpus;
        const int here = sched_getcpu();
        if (here >= 0 && here < CPU_SETSIZE) CPU_CLR(here, &others);
        // With no other CPU left the thread shares this one, as it would anyway.
        if (CPU_COUNT(&others) > 0) pthread_attr_setaffinity_np(&attr, sizeof others, &others);
    }
    pthread_t thread;
    const bool made = pthread_create(&thread, &attr, &serve_pinned, nullptr) == 0;
    pthread_attr_destroy(&attr);
    if (made) pthread_detach(thread);
    return made;
}

bool process_cpus(cpu_set_t& cpus) {
    CPU_ZERO(&cpus);
    // Fails (EINVAL) where the kernel's masks are wider than cpu_set_t (over 1024 CPUs).
    return sched_getaffinity(0, sizeof cpus, &cpus) == 0 && CPU_COUNT(&cpus) > 0;
}
#else
bool make_helper(Pool& p) {
    try {
        std::thread([&p] { serve(p.numbered++); }).detach();
        return true;
    } catch (const std::system_error&) {
        return false;
    }
}
#endif

#ifndef _WIN32
// While one lives, this thread has the interrupts blocked, and every thread it starts
// has them blocked for good: the handlers run on the main thread only (interrupts.h).
class InterruptsBlocked {
public:
    InterruptsBlocked() {
        sigset_t interrupts;
        sigemptyset(&interrupts);
        add_interrupt_signals(interrupts);
        blocked_ = pthread_sigmask(SIG_BLOCK, &interrupts, &before_) == 0;
    }
    ~InterruptsBlocked() {
        if (blocked_) (void)pthread_sigmask(SIG_SETMASK, &before_, nullptr);
    }
    InterruptsBlocked(const InterruptsBlocked&) = delete;
    InterruptsBlocked& operator=(const InterruptsBlocked&) = delete;

private:
    sigset_t before_;
    bool blocked_;
};
#endif

}  // namespace

unsigned available_cores() {
#if RT_HELPERS_PINNED_START
    cpu_set_t cpus;
    if (process_cpus(cpus)) return static_cast<unsigned>(CPU_COUNT(&cpus));
#endif
    const unsigned cores = std::thread::hardware_concurrency();
    return cores == 0 ? 1 : cores;
}

unsigned HelperPool::Job::start(unsigned helpers, Body body, void* context) {
    finish();
    if (helpers == 0) return 0;
    Pool& p = pool();
    if (!p.job_mutex.try_lock()) return 0;  // another render has the helpers
#if RT_HELPERS_PINNED_START
    if (p.threads == 0) p.have_process_cpus = process_cpus(p.process_cpus);
#endif
    p.body = body;
    p.context = context;
    p.helpers = helpers;
    {
        // Opened only while not retired, in one step with the check.
        const std::lock_guard<std::mutex> lock(p.wake_mutex);
        started_ = !p.retired;
        if (started_) p.state.store((((p.state.load() >> 1) + 1) << 1) | 1U);
    }
    if (!started_) {
        p.job_mutex.unlock();
        return 0;
    }
    p.wake.notify_all();  // the helpers made before
    // The helpers still missing see the open job as soon as they run.
    if (p.threads < helpers) {
#ifndef _WIN32
        const InterruptsBlocked in_new_helpers;
#endif
        while (p.threads < helpers && make_helper(p)) ++p.threads;
    }
    return p.threads < helpers ? p.threads : helpers;
}

void HelperPool::Job::finish() {
    if (!started_) return;
    Pool& p = pool();
    p.state.store(p.state.load() & ~std::uint64_t(1));  // closed: no helper enters now
    // The helpers inside are mostly on their last band of rows, about to leave: this
    // thread yields meanwhile, then sleeps, so that a helper kept long (its write to a
    // pipe that is not read, half of a large tree's build) costs no core.
    const auto yield_until = std::chrono::steady_clock::now() + kYieldBeforeSleep;
    while (p.inside.load() != 0 && std::chrono::steady_clock::now() < yield_until) std::this_thread::yield();
    if (p.inside.load() != 0) {
        std::unique_lock<std::mutex> lock(p.wake_mutex);
        p.finisher_asleep.store(true);
        p.all_left.wait(lock, [&p] { return p.inside.load() == 0; });
        p.finisher_asleep.store(false);
    }
    started_ = false;
    p.job_mutex.unlock();
}

void HelperPool::retire() {
    Pool& p = pool();
    {
        const std::lock_guard<std::mutex> lock(p.wake_mutex);
        p.retired = true;
    }
    p.wake.notify_all();
}

bool HelperPool::starts_on_idle_core() { return RT_HELPERS_PINNED_START != 0; }

}  // namespace rt
