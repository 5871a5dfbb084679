// What an interrupted run (SIGINT, SIGTERM, SIGHUP; Ctrl+C and Ctrl+Break on Windows)
// does: removes the named temporary file being written, if any, prints one line saying
// so, and exits with 128 + the signal's number. SIGXFSZ is ignored, so that a file-size
// limit (ulimit -f) makes a write fail, reported like a full disk, instead of killing
// the process silently.
#pragma once

namespace rt {

// Installs the handlers; call once, before the output file is created.
void install_interrupt_handlers();

// The named temporary file a handler must remove. The path is copied into a fixed
// buffer the handler can read; one longer than the buffer is refused (returns false)
// and the caller must use another name.
bool set_interrupt_cleanup(const char* path);
#ifdef _WIN32
bool set_interrupt_cleanup(const wchar_t* path);  // any Unicode path
#endif
// No file for a handler to remove (it has been removed, or renamed into place).
void clear_interrupt_cleanup();

// Whether a progress line is on the terminal: a handler erases it before its message.
void set_interrupt_erases_line(bool erase);

// Erases a line by overwriting it with spaces, which every terminal and the Windows
// console understand (an ANSI "erase line" is not understood by older consoles). Every
// progress line drawn is shorter.
inline constexpr const char* kEraseLine =
    "\r                                                                               \r";

}  // namespace rt
