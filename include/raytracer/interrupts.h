// What an interrupted run (SIGINT, SIGTERM, SIGHUP; Ctrl+C and Ctrl+Break on Windows)
// does: removes the named temporary file being written, if any, prints one line saying
// so, and exits with 128 + the signal's number; once the image is being put in place,
// nothing (hold_interrupts()). SIGQUIT, SIGPIPE, SIGALRM, SIGVTALRM, SIGPROF, SIGUSR1,
// SIGUSR2 and SIGXCPU, where their default action stands, keep it and its exit status,
// silently, but remove the named temporary first; while the image is being put in place
// under a named temporary, they end the run once it is (clear_interrupt_cleanup()), so
// that no temporary stays. A signal that was ignored when the program started (nohup)
// stays ignored. SIGXFSZ is ignored, so that a file-size limit (ulimit -f) makes a write
// fail, reported like a full disk, instead of killing the process silently.
#pragma once

#ifndef _WIN32
#include <csignal>
#endif

namespace rt {

// Installs the handlers; call once, before the scene is read.
void install_interrupt_handlers();
#ifndef _WIN32
// The signals the handlers take (SIGINT, SIGTERM, SIGHUP), added to set. The helper
// threads start with them blocked (helper_pool.cpp), so that a handler runs on the main
// thread only, the one that draws the progress line (progress.cpp): never beside a
// redraw, and no line is drawn after its message. (Windows runs a console's handler on
// a thread of its own. The other ending signals' handler, which writes nothing, may run
// on any thread.)
void add_interrupt_signals(sigset_t& set);
#endif

// The image is about to be put in place (PendingFile::commit()): from this call on, an
// interrupt is ignored, since its handler would otherwise run after the image is in
// place and say "no image written". Where a handler is already ending the program (on
// another thread), this waits for it and never returns, so the image is not put in
// place behind its back.
void hold_interrupts();
// The image was not put in place after all (an error): interrupts end the program again.
void release_interrupts();

// The named temporary file a handler must remove. The path is copied into a fixed
// buffer the handler can read; one longer than the buffer is refused (returns false)
// and the caller must use another name.
#ifdef _WIN32
bool set_interrupt_cleanup(const wchar_t* path);  // any Unicode path
#else
// The name in an open folder (a descriptor, which must stay open until the cleanup is
// cleared): removed with unlinkat(), wherever the folder's path leads by then.
bool set_interrupt_cleanup(int folder, const char* name);
#endif
// No file for a handler to remove (it has been removed, or renamed into place). An
// ending signal that came while the image was being put in place ends the run here.
void clear_interrupt_cleanup();

// The length of the progress line on the terminal (0: none): a handler erases that
// many characters before its message. At most kMaxErasedLine.
inline constexpr int kMaxErasedLine = 160;
void set_interrupt_erases_line(int length);
// Whether part of the image may already be out: it goes straight to a stream (standard
// output, a FIFO, a device) and its first bytes have been written (PendingFile::write()).
// The message then says it is incomplete, not that no image was written.
void set_interrupt_output_is_stream(bool stream);

// While one lives, a write on this thread to a pipe whose reader is gone fails with
// EPIPE instead of raising SIGPIPE. Around writes to standard error, so that a reader of
// it gone (2>&1 | head) loses the messages and the progress line, not the image nor the
// exit status; a reader of the image gone still ends the run by SIGPIPE. (POSIX; on
// Windows a write to a closed pipe fails without a signal.)
class QuietBrokenPipe {
public:
    QuietBrokenPipe();
    ~QuietBrokenPipe();
    QuietBrokenPipe(const QuietBrokenPipe&) = delete;
    QuietBrokenPipe& operator=(const QuietBrokenPipe&) = delete;

private:
#ifndef _WIN32
    sigset_t before_{};  // this thread's mask before
    // A SIGPIPE was pending already: not this one's to take.
    bool pending_before_ = false;
#endif
};

}  // namespace rt
