#include "child_process.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#ifdef _WIN32
#include <windows.h>
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#endif

namespace grade {
namespace {

volatile std::sig_atomic_t g_interrupting_signal = 0;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int interrupting_signal() { return g_interrupting_signal; }

std::string signal_name(int signal) {
    switch (signal) {
        case SIGSEGV:
            return "SIGSEGV";
        case SIGABRT:
            return "SIGABRT";
        case SIGFPE:
            return "SIGFPE";
        case SIGILL:
            return "SIGILL";
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
#ifndef _WIN32
        case SIGKILL:
            return "SIGKILL";
        case SIGBUS:
            return "SIGBUS";
        case SIGPIPE:
            return "SIGPIPE";
#endif
        default:
            return "signal " + std::to_string(signal);
    }
}

std::string windows_crash_name(unsigned long code) {
    switch (code) {
        case 0xC0000005UL:
            return "an access violation (0xC0000005, like SIGSEGV)";
        case 0xC00000FDUL:
            return "a stack overflow (0xC00000FD)";
        case 0xC0000094UL:
            return "an integer division by zero (0xC0000094, like SIGFPE)";
        case 0xC000001DUL:
            return "an illegal instruction (0xC000001D, like SIGILL)";
        case 0xC0000409UL:
            return "a fast fail, as abort() does (0xC0000409, like SIGABRT)";
        default:
            break;
    }
    if (code >= 0xC0000000UL) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%08lX", code);
        return std::string("an exception ") + hex;
    }
    return {};
}

#ifdef _WIN32

namespace {

BOOL WINAPI on_console_event(DWORD /*event*/) {
    g_interrupting_signal = SIGINT;
    return TRUE;
}

std::wstring quoted(const std::wstring& text) { return L"\"" + text + L"\""; }

// The file made anew (NUL as it is), for a child to inherit.
HANDLE inheritable_output(const wchar_t* file, DWORD disposition) {
    SECURITY_ATTRIBUTES attributes{sizeof(SECURITY_ATTRIBUTES), nullptr, TRUE};
    return CreateFileW(file, GENERIC_WRITE, FILE_SHARE_READ | FILE_SHARE_WRITE, &attributes, disposition,
                       FILE_ATTRIBUTE_NORMAL, nullptr);
}

}  // namespace

void install_interrupt_handlers() {
    SetConsoleCtrlHandler(on_console_event, TRUE);
    // No "program has stopped working" dialog for a crashing child: it inherits this mode.
    SetErrorMode(SEM_FAILCRITICALERRORS | SEM_NOGPFAULTERRORBOX);
}

ChildOutcome run_child(const ChildCommand& command) {
    ChildOutcome outcome;
    std::wstring line = quoted(command.program.wstring());
    for (const std::string& arg : command.args) line += L" " + quoted(std::filesystem::u8path(arg).wstring());
    HANDLE out = inheritable_output(L"NUL", OPEN_EXISTING);
    HANDLE err = inheritable_output(command.stderr_file.wstring().c_str(), CREATE_ALWAYS);
    STARTUPINFOW startup{};
    startup.cb = sizeof startup;
    startup.dwFlags = STARTF_USESTDHANDLES;
    // Standard input from NUL: a program that waits for Enter at its end gets end of
    // file at once, as on POSIX.
    SECURITY_ATTRIBUTES inherited{sizeof(SECURITY_ATTRIBUTES), nullptr, TRUE};
    HANDLE in = CreateFileW(L"NUL", GENERIC_READ, FILE_SHARE_READ | FILE_SHARE_WRITE, &inherited,
                            OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, nullptr);
    startup.hStdInput = in;
    startup.hStdOutput = out;
    startup.hStdError = err;
    PROCESS_INFORMATION process{};
    const std::wstring folder = command.folder.wstring();
    const auto start = Clock::now();
    const BOOL started = CreateProcessW(command.program.wstring().c_str(), line.data(), nullptr, nullptr,
                                        TRUE, 0, nullptr, folder.c_str(), &startup, &process);
    CloseHandle(in);
    CloseHandle(out);
    CloseHandle(err);
    if (!started) {
        outcome.why_not_started = "Windows error " + std::to_string(GetLastError());
        return outcome;
    }
    CloseHandle(process.hThread);
    outcome.end = ChildOutcome::End::exited;
    while (WaitForSingleObject(process.hProcess, 20) == WAIT_TIMEOUT) {
        const bool late = seconds_since(start) > command.timeout_seconds;
        if (late || interrupting_signal() != 0) {
            TerminateProcess(process.hProcess, 1);
            WaitForSingleObject(process.hProcess, INFINITE);
            outcome.end = late ? ChildOutcome::End::timed_out : ChildOutcome::End::interrupted;
            break;
        }
    }
    outcome.seconds = seconds_since(start);
    DWORD code = 0;
    GetExitCodeProcess(process.hProcess, &code);
    CloseHandle(process.hProcess);
    outcome.code = static_cast<int>(code);
    return outcome;
}

#else

namespace {

extern "C" void grader_on_interrupt(int signal) { g_interrupting_signal = signal; }

// In the forked child: only async-signal-safe calls until execv. On failure the errno goes
// up the close-on-exec pipe, so that the grader can say why the program did not start.
[[noreturn]] void exec_child(const ChildCommand& command, char* const* argv, int report_fd) {
    setpgid(0, 0);  // its own process group: the whole group is killed on a timeout
    // Standard input from /dev/null: a program that waits for Enter at its end gets end
    // of file at once, the same on a terminal as in CI (in a process group of its own, a
    // read from the terminal would stop it with SIGTTIN until the timeout).
    const int in = open("/dev/null", O_RDONLY);
    const int out = open("/dev/null", O_WRONLY);
    // Appended to, so that the file can be cut back under it (cut_back()).
    const int err = open(command.stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
    if (in >= 0 && out >= 0 && err >= 0 && dup2(in, 0) >= 0 && dup2(out, 1) >= 0 && dup2(err, 2) >= 0 &&
        chdir(command.folder.c_str()) == 0) {
        for (const int fd : {in, out, err})  // the program gets 0, 1 and 2, not copies besides
            if (fd > 2) close(fd);
        execv(argv[0], argv);
    }
    const int error = errno;
    if (write(report_fd, &error, sizeof error) < 0) _exit(127);
    _exit(127);
}

// Cuts the file back to `kept` bytes once it holds twice that: the program's appends go
// on after them.
void cut_back(const std::filesystem::path& file, std::uintmax_t kept) {
    struct stat s {};
    if (kept > 0 && ::stat(file.c_str(), &s) == 0 && static_cast<std::uintmax_t>(s.st_size) > 2 * kept)
        (void)::truncate(file.c_str(), static_cast<off_t>(kept));
}

void kill_and_reap(pid_t pid, int& status) {
    kill(-pid, SIGKILL);
    kill(pid, SIGKILL);
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
}

}  // namespace

void install_interrupt_handlers() {
    struct sigaction action {};
    action.sa_handler = grader_on_interrupt;
    sigemptyset(&action.sa_mask);
    // SIGHUP: the terminal closed; SIGPIPE: the report's reader went (| head): each stops
    // the grading as an interrupt does, so that the scratch folder is removed.
    for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaction(signal, &action, nullptr);
}

ChildOutcome run_child(const ChildCommand& command) {
    ChildOutcome outcome;
    std::vector<std::string> strings = {command.program.string()};
    strings.insert(strings.end(), command.args.begin(), command.args.end());
    std::vector<char*> argv;
    argv.reserve(strings.size() + 1);
    for (std::string& s : strings) argv.push_back(s.data());
    argv.push_back(nullptr);

    int report[2];
    if (pipe(report) != 0 || fcntl(report[1], F_SETFD, FD_CLOEXEC) != 0) {
        outcome.why_not_started = std::strerror(errno);
        return outcome;
    }
    const auto start = Clock::now();
    const pid_t pid = fork();
    if (pid == 0) exec_child(command, argv.data(), report[1]);
    close(report[1]);
    int exec_error = 0;
    const bool exec_failed = pid > 0 && read(report[0], &exec_error, sizeof exec_error) == sizeof exec_error;
    close(report[0]);
    if (pid < 0 || exec_failed) {
        int status = 0;
        if (pid > 0) waitpid(pid, &status, 0);
        outcome.why_not_started = std::strerror(pid < 0 ? errno : exec_error);
        return outcome;
    }

    int status = 0;
    outcome.end = ChildOutcome::End::exited;
    auto pause = std::chrono::microseconds(100);  // grows to 10 ms: quick renders are timed closely
    // Until it ends; then whatever it started in its group goes too (kill_and_reap), before
    // it is reaped, so that the group's number cannot have been given to another.
    for (;;) {
        siginfo_t ended{};
        const bool late = seconds_since(start) > command.timeout_seconds;
        if (waitid(P_PID, static_cast<id_t>(pid), &ended, WEXITED | WNOHANG | WNOWAIT) == 0 &&
            ended.si_pid != 0) {
            kill_and_reap(pid, status);
            break;
        }
        if (late || interrupting_signal() != 0) {
            kill_and_reap(pid, status);
            outcome.end = late ? ChildOutcome::End::timed_out : ChildOutcome::End::interrupted;
            break;
        }
        cut_back(command.stderr_file, command.stderr_kept);
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(10000));
    }
    outcome.seconds = seconds_since(start);
    if (outcome.end == ChildOutcome::End::exited && WIFSIGNALED(status)) {
        outcome.end = ChildOutcome::End::killed_by_signal;
        outcome.code = WTERMSIG(status);
    } else if (outcome.end == ChildOutcome::End::exited) {
        outcome.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    return outcome;
}

#endif

}  // namespace grade
