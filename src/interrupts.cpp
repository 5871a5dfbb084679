#include "raytracer/interrupts.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstddef>
#include <cstring>
#include <cwchar>
#include <initializer_list>
#include <thread>

#ifdef _WIN32
#include <io.h>  // _write
#include <stdlib.h>
#else
#include <fcntl.h>    // unlinkat
#include <pthread.h>  // pthread_sigmask
#include <unistd.h>   // write, _exit, pause
#endif

namespace rt {
namespace {

// The handlers read only these, take `phase` below by a compare-exchange, and call only
// unlinkat (_wunlink on Windows), write and _exit (end_on_signal(): signal, raise and
// pause; on Windows, signal() to stay installed), which are async-signal-safe. A name
// is copied into cleanup_path before cleanup_set is raised, so a handler never sees
// half a name: the flags are lock-free atomics, stored with release (or stronger) and
// loaded with acquire, as a handler may run on another thread than the one that sets
// them (on Windows a thread of its own; elsewhere the main thread, or a helper for the
// ending signals), where a fence for signals alone would not order the name before the
// flag.
static_assert(std::atomic<int>::is_always_lock_free, "a signal handler may use only lock-free atomics");
constexpr std::size_t kMaxPath = 4096;
#ifdef _WIN32
wchar_t cleanup_wide_path[kMaxPath];
#else
char cleanup_path[kMaxPath];
#endif
std::atomic<int> cleanup_set{0};  // 1: a name is set
#ifndef _WIN32
std::atomic<int> cleanup_folder{-1};  // the folder cleanup_path is in (unlinkat())
#endif
// The progress line's length (0: none). The handler erases the line by overwriting it:
// "\r", that many spaces, "\r", which every terminal and the Windows console understand
// (an ANSI "erase line" is not understood by older consoles). The spaces are a constant,
// so a progress line redrawn on another thread while a handler writes them changes
// nothing the handler reads but this one number.
std::atomic<int> erase_length{0};
struct Blanks {
    char text[1 + kMaxErasedLine];  // "\r" and the spaces
};
constexpr Blanks make_blanks() {
    Blanks blanks{};
    for (char& c : blanks.text) c = ' ';
    blanks.text[0] = '\r';
    return blanks;
}
constexpr Blanks kBlanks = make_blanks();
std::atomic<int> output_is_stream{0};
// Who ends the run: kRunning until a handler takes kInterrupted (and exits) or
// hold_interrupts() takes kHeld (the image is being put in place), whichever is first:
// one compare-exchange each, so that exactly one of them wins.
enum Phase : int { kRunning, kHeld, kInterrupted };
std::atomic<int> phase{kRunning};
#ifndef _WIN32
// An ending signal that came while a named temporary was being put in place: the run
// ends by it once no named temporary is left (clear_interrupt_cleanup()). It and
// cleanup_set are stored and then the other loaded, all sequentially consistent, so at
// least one side sees the other's store: the signal is never lost, and never acted on
// while a temporary would stay.
std::atomic<int> deferred_signal{0};
constexpr int kInterruptSignals[] = {SIGINT, SIGTERM, SIGHUP};
// The other signals that end a process by default (Ctrl-\, a reader of the image gone,
// timers, the user's): they keep their default action and exit status (SIGQUIT's core,
// SIGPIPE's silent 141), but the named temporary is removed first, or, while the image
// is being put in place, the run ends once it is.
constexpr int kEndingSignals[] = {SIGQUIT, SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2, SIGVTALRM, SIGPROF, SIGXCPU};
#endif

void say(const char* text, std::size_t length) {
#ifdef _WIN32
    (void)_write(2, text, static_cast<unsigned>(length));
#else
    (void)!write(2, text, length);
#endif
}
void say(const char* text) { say(text, std::strlen(text)); }

// Removes the named temporary a cleanup is set for, if any (from a handler).
void remove_cleanup_file() {
    if (cleanup_set.load(std::memory_order_acquire) == 0) return;
#ifdef _WIN32
    (void)_wunlink(cleanup_wide_path);
#else
    (void)unlinkat(cleanup_folder.load(std::memory_order_relaxed), cleanup_path, 0);
#endif
}

extern "C" void render_on_interrupt(int signal_number) {
    int running = kRunning;
    if (!phase.compare_exchange_strong(running, kInterrupted)) {  // the image is (being) put in place
#ifdef _WIN32
        (void)std::signal(signal_number, render_on_interrupt);  // Windows reset it to SIG_DFL before the call
#endif
        return;
    }
    remove_cleanup_file();
    if (const int erase = erase_length.load(std::memory_order_relaxed); erase > 0) {
        say(kBlanks.text, 1 + static_cast<std::size_t>(erase));
        say("\r");
    }
    const char* name = "a signal";
    if (signal_number == SIGINT) name = "SIGINT";
    if (signal_number == SIGTERM) name = "SIGTERM";
#ifdef SIGHUP
    if (signal_number == SIGHUP) name = "SIGHUP";
#endif
    say("raytracer.exe: error: interrupted by ");
    say(name);
    say(output_is_stream.load(std::memory_order_relaxed) != 0 ? ", the image written so far is incomplete\n"
                                                              : ", no image written\n");
    _exit(128 + signal_number);
}

#ifndef _WIN32
void end_by(int signal_number) {
    (void)std::signal(signal_number, SIG_DFL);
    (void)std::raise(signal_number);  // in a handler, blocked: it ends the process once that returns
}

extern "C" void end_on_signal(int signal_number) {
    int running = kRunning;
    if (phase.compare_exchange_strong(running, kInterrupted)) {
        remove_cleanup_file();
    } else if (running == kInterrupted) {
        for (;;) pause();  // another handler is ending the run, its temporary first
    } else {
        // The image is being put in place. Its temporary, if named, is not removed (the
        // rename may be done, or next), and the process may not end and leave it: the
        // run ends by this signal once the temporary is gone.
        deferred_signal.store(signal_number);
        if (cleanup_set.load() != 0) return;
    }
    end_by(signal_number);
}

// Ends the run by a signal that waited for the named temporary (end_on_signal()).
void end_by_deferred_signal() {
    if (const int signal_number = deferred_signal.load(); signal_number != 0) end_by(signal_number);
}
#endif

}  // namespace

// A signal ignored when the program started stays ignored (nohup, a shell's background
// job, a script's trap '' TERM), as POSIX asks of interactive programs' handlers.
void install_interrupt_handlers() {
#ifdef _WIN32
    for (const int s : {SIGINT, SIGTERM, SIGBREAK})
        if (std::signal(s, render_on_interrupt) == SIG_IGN) (void)std::signal(s, SIG_IGN);
#else
    // One handler of either kind at a time on a thread: a second signal waits until the
    // first has exited (a nested one would end the run before the first had removed the
    // temporary).
    sigset_t handled;
    sigemptyset(&handled);
    add_interrupt_signals(handled);
    for (const int s : kEndingSignals) (void)sigaddset(&handled, s);
    struct sigaction action {};
    action.sa_handler = render_on_interrupt;
    action.sa_flags = SA_RESTART;  // a handler may return (hold_interrupts()): no EINTR
    action.sa_mask = handled;
    for (const int s : kInterruptSignals) {
        struct sigaction before {};
        if (sigaction(s, nullptr, &before) == 0 && before.sa_handler == SIG_IGN) continue;
        (void)sigaction(s, &action, nullptr);
    }
    // Only where the default action stands: an ignored signal, or a handler installed
    // before main() (a profiler's SIGPROF, say), is left as it is.
    struct sigaction ending {};
    ending.sa_handler = end_on_signal;
    ending.sa_flags = SA_RESTART;  // it returns while the image is put in place: no EINTR
    ending.sa_mask = handled;
    for (const int s : kEndingSignals) {
        struct sigaction before {};
        if (sigaction(s, nullptr, &before) != 0 || before.sa_handler != SIG_DFL ||
            (before.sa_flags & SA_SIGINFO) != 0)
            continue;
        (void)sigaction(s, &ending, nullptr);
    }
    (void)std::signal(SIGXFSZ, SIG_IGN);
#endif
}

#ifndef _WIN32
void add_interrupt_signals(sigset_t& set) {
    for (const int s : kInterruptSignals) (void)sigaddset(&set, s);
}
#endif

void hold_interrupts() {
    int running = kRunning;
    if (phase.compare_exchange_strong(running, kHeld) || running == kHeld) return;
    for (;;) std::this_thread::sleep_for(std::chrono::hours(1));  // the handler is exiting
}

void release_interrupts() {
    int held = kHeld;
    (void)phase.compare_exchange_strong(held, kRunning);
}

void clear_interrupt_cleanup() {
    cleanup_set.store(0);
#ifndef _WIN32
    end_by_deferred_signal();
#endif
}

#ifndef _WIN32
bool set_interrupt_cleanup(int folder, const char* name) {
    cleanup_set.store(0, std::memory_order_release);
    const std::size_t length = std::strlen(name);
    if (length >= kMaxPath) return false;
    std::memcpy(cleanup_path, name, length + 1);
    cleanup_folder.store(folder, std::memory_order_relaxed);
    cleanup_set.store(1);  // the name and folder are set before the flag
    // A signal is ending the run (end_on_signal()): no temporary is named now.
    if (deferred_signal.load() != 0) {
        cleanup_set.store(0);
        end_by_deferred_signal();
    }
    return true;
}
#else
bool set_interrupt_cleanup(const wchar_t* path) {
    cleanup_set.store(0, std::memory_order_release);
    const std::size_t length = std::wcslen(path);
    if (length >= kMaxPath) return false;
    std::wmemcpy(cleanup_wide_path, path, length + 1);
    cleanup_set.store(1, std::memory_order_release);  // the path is complete before the flag
    return true;
}
#endif

void set_interrupt_erases_line(int length) {
    erase_length.store(std::clamp(length, 0, kMaxErasedLine), std::memory_order_relaxed);
}

void set_interrupt_output_is_stream(bool stream) {
    output_is_stream.store(stream ? 1 : 0, std::memory_order_relaxed);
}

#ifdef _WIN32
QuietBrokenPipe::QuietBrokenPipe() = default;
QuietBrokenPipe::~QuietBrokenPipe() = default;
#else
namespace {
sigset_t broken_pipe() {
    sigset_t set;
    sigemptyset(&set);
    (void)sigaddset(&set, SIGPIPE);
    return set;
}
}  // namespace

QuietBrokenPipe::QuietBrokenPipe() {
    sigset_t pending;
    pending_before_ = sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1;
    const sigset_t pipe = broken_pipe();
    (void)pthread_sigmask(SIG_BLOCK, &pipe, &before_);
}

// The SIGPIPE a failed write raised is pending on this thread, blocked: taken here
// (sigwait returns at once, as it is pending) before the mask is restored.
QuietBrokenPipe::~QuietBrokenPipe() {
    sigset_t pending;
    if (!pending_before_ && sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1) {
        const sigset_t pipe = broken_pipe();
        int taken = 0;
        (void)sigwait(&pipe, &taken);
    }
    (void)pthread_sigmask(SIG_SETMASK, &before_, nullptr);
}
#endif

}  // namespace rt
