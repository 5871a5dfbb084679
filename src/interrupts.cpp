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
// "\r", as many spaces as the progress line has characters, "\r": a line is erased by
// overwriting it, which every terminal and the Windows console understand (an ANSI
// "erase line" is not understood by older consoles). Set before erase_line is raised.
char erase_text[kMaxErasedLine + 3];
volatile std::sig_atomic_t erase_line = 0;
volatile std::sig_atomic_t output_is_stream = 0;

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
    if (erase_line != 0) say(erase_text);
    const char* name = "a signal";
    if (signal_number == SIGINT) name = "SIGINT";
    if (signal_number == SIGTERM) name = "SIGTERM";
#ifdef SIGHUP
    if (signal_number == SIGHUP) name = "SIGHUP";
#endif
    say("raytracer.exe: error: interrupted by ");
    say(name);
    say(output_is_stream != 0 ? ", the image written so far is incomplete\n" : ", no image written\n");
    _exit(128 + signal_number);
}

}  // namespace

// A signal ignored when the program started stays ignored (nohup, a shell's background
// job, a script's trap '' TERM), as POSIX asks of interactive programs' handlers.
void install_interrupt_handlers() {
#ifdef _WIN32
    for (const int s : {SIGINT, SIGTERM, SIGBREAK})
        if (std::signal(s, render_on_interrupt) == SIG_IGN) (void)std::signal(s, SIG_IGN);
#else
    struct sigaction action {};
    action.sa_handler = render_on_interrupt;
    sigemptyset(&action.sa_mask);
    // One handler at a time: a second signal waits until the first has exited.
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) (void)sigaddset(&action.sa_mask, s);
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction before {};
        if (sigaction(s, nullptr, &before) == 0 && before.sa_handler == SIG_IGN) continue;
        (void)sigaction(s, &action, nullptr);
    }
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

void set_interrupt_erases_line(int length) {
    erase_line = 0;
    if (length <= 0) return;
    const auto n = static_cast<std::size_t>(length < kMaxErasedLine ? length : kMaxErasedLine);
    erase_text[0] = '\r';
    std::memset(erase_text + 1, ' ', n);
    erase_text[n + 1] = '\r';
    erase_text[n + 2] = '\0';
    std::atomic_signal_fence(std::memory_order_seq_cst);  // the text is complete before the flag
    erase_line = 1;
}

void set_interrupt_output_is_stream(bool stream) { output_is_stream = stream ? 1 : 0; }

}  // namespace rt
