#include "raytracer/interrupts.h"

#include <atomic>
#include <csignal>
#include <cstddef>
#include <cstring>
#include <cwchar>
#include <initializer_list>

#ifdef _WIN32
#include <io.h>  // _unlink, _write
#include <stdlib.h>
#else
#include <unistd.h>  // unlink, write, _exit
#endif

namespace rt {
namespace {

// The handler reads only these, and calls only unlink, write and _exit, which are
// async-signal-safe. A path is copied into cleanup_path before cleanup_set is raised,
// so the handler never sees half a path.
constexpr std::size_t kMaxPath = 4096;
char cleanup_path[kMaxPath];
#ifdef _WIN32
wchar_t cleanup_wide_path[kMaxPath];
#endif
volatile std::sig_atomic_t cleanup_set = 0;  // 1: cleanup_path, 2: cleanup_wide_path
volatile std::sig_atomic_t erase_line = 0;

void say(const char* text) {
#ifdef _WIN32
    (void)_write(2, text, static_cast<unsigned>(std::strlen(text)));
#else
    (void)!write(2, text, std::strlen(text));
#endif
}

extern "C" void render_on_interrupt(int signal_number) {
#ifdef _WIN32
    if (cleanup_set == 1) (void)_unlink(cleanup_path);
    if (cleanup_set == 2) (void)_wunlink(cleanup_wide_path);
#else
    if (cleanup_set != 0) (void)unlink(cleanup_path);
#endif
    if (erase_line != 0) say(kEraseLine);
    const char* name = "a signal";
    if (signal_number == SIGINT) name = "SIGINT";
    if (signal_number == SIGTERM) name = "SIGTERM";
#ifdef SIGHUP
    if (signal_number == SIGHUP) name = "SIGHUP";
#endif
    say("raytracer.exe: error: interrupted by ");
    say(name);
    say(", no image written\n");
    _exit(128 + signal_number);
}

}  // namespace

void install_interrupt_handlers() {
#ifdef _WIN32
    (void)std::signal(SIGINT, render_on_interrupt);
    (void)std::signal(SIGTERM, render_on_interrupt);
    (void)std::signal(SIGBREAK, render_on_interrupt);
#else
    struct sigaction action {};
    action.sa_handler = render_on_interrupt;
    sigemptyset(&action.sa_mask);
    // One handler at a time: a second signal waits until the first has exited.
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) (void)sigaddset(&action.sa_mask, s);
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) (void)sigaction(s, &action, nullptr);
    (void)std::signal(SIGXFSZ, SIG_IGN);
#endif
}

void clear_interrupt_cleanup() { cleanup_set = 0; }

bool set_interrupt_cleanup(const char* path) {
    cleanup_set = 0;
    const std::size_t length = std::strlen(path);
    if (length >= kMaxPath) return false;
    std::memcpy(cleanup_path, path, length + 1);
    std::atomic_signal_fence(std::memory_order_seq_cst);  // the path is complete before the flag
    cleanup_set = 1;
    return true;
}

#ifdef _WIN32
bool set_interrupt_cleanup(const wchar_t* path) {
    cleanup_set = 0;
    const std::size_t length = std::wcslen(path);
    if (length >= kMaxPath) return false;
    std::wmemcpy(cleanup_wide_path, path, length + 1);
    std::atomic_signal_fence(std::memory_order_seq_cst);  // the path is complete before the flag
    cleanup_set = 2;
    return true;
}
#endif

void set_interrupt_erases_line(bool erase) { erase_line = erase ? 1 : 0; }

}  // namespace rt
