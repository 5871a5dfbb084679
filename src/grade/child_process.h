// Runs the program under test as a child process with a time limit, in a given working
// folder, its stdin from and stdout to the null device (/dev/null, NUL: nothing of its
// output is read), its stderr to a file; a child that outlives the limit, or the
// grader's own interruption (SIGINT, SIGTERM, SIGHUP, SIGPIPE, Ctrl-C), is killed and
// reaped, and on POSIX so is what it leaves running in its process group. POSIX: fork,
// execv, waitpid in a poll loop; Windows: CreateProcessW, WaitForSingleObject.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace grade {

struct ChildCommand {
    std::filesystem::path program;
    std::vector<std::string> args;
    std::filesystem::path folder;  // the working folder
    std::filesystem::path stderr_file;
    double timeout_seconds = 60;
    // POSIX: the bytes of stderr kept; past twice that, the file is cut back to it while
    // the program runs, so that one that writes without end cannot fill the disk.
    std::uintmax_t stderr_kept = std::uintmax_t{1} << 20;
};

struct ChildOutcome {
    enum class End { exited, killed_by_signal, timed_out, interrupted, not_started };
    End end = End::not_started;
    int code = 0;        // the exit status, or the signal number (killed_by_signal)
    double seconds = 0;  // wall time from start to end
    std::string why_not_started;
};

// Makes SIGINT and SIGTERM (Ctrl-C on Windows) set a flag instead of ending the grader,
// so that it can kill its child and remove its scratch folder first.
void install_interrupt_handlers();
// The signal that interrupted the grader, or 0.
int interrupting_signal();

ChildOutcome run_child(const ChildCommand& command);

// "SIGSEGV" for 11 on Linux, and so on; "signal N" for the rarer ones.
std::string signal_name(int signal);

// On Windows a crash is an exit code such as 0xC0000005: its description ("an access
// violation, like SIGSEGV"), or an empty string for an ordinary exit status.
std::string windows_crash_name(unsigned long code);

}  // namespace grade
