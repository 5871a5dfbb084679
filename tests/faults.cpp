// Faults around a render (issue 17), on the real raytracer.exe started as a child
// process: signals sent mid-render, a file-size limit, permissions kept, long names,
// devices and FIFOs, the scene file named as OUTPUT through other names, and the
// progress line on a pseudo-terminal. POSIX's: faults_windows.cpp holds Windows'.
#include <dirent.h>
#include <fcntl.h>
#include <grp.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "check.h"
#include "process_scratch.h"
#include "raytracer/compiler.h"
#include "raytracer/interrupts.h"
#include "raytracer/output_file.h"

#ifndef RAYTRACER_EXE
#error "RAYTRACER_EXE must name the raytracer.exe under test"
#endif

namespace fs = std::filesystem;
using namespace process_scratch;

namespace {

struct Options {
    bool named_temporary = false;         // RAYTRACER_NAMED_TEMPORARY: the fallback of other systems
    long file_size_limit = -1;            // RLIMIT_FSIZE in bytes; -1: none
    int stderr_fd = -1;                   // where the child's stderr goes; -1: the capture file
    int stdout_fd = -1;                   // where the child's stdout goes; -1: the capture file
    long address_space_limit = -1;        // RLIMIT_AS in bytes; -1: none
    bool ignore_hangup_and_term = false;  // started as nohup and trap '' TERM start it
    unsigned closed_streams = 0;          // bit k: started with descriptor k closed (2>&- is 4)
    int stdin_fd = -1;                    // where the child's stdin comes from; -1: this process's
    uid_t user = 0;                       // run as this user and its group (by root); 0: as this one
    int descriptor_3 = -1;                // what the child's descriptor 3 is; -1: as inherited
};

// Starts raytracer.exe with args in folder.work; stdout and stderr go to files in root.
pid_t start(const Scratch& folder, const std::vector<std::string>& args, const Options& options = {}) {
    const std::string out = (folder.root / "stdout").string(), err = (folder.root / "stderr").string();
    const std::string work = folder.work.string();
    std::vector<std::string> all = {RAYTRACER_EXE};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    argv.reserve(all.size() + 1);
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid != 0) return pid;
    // The child: only calls that are safe after fork, then exec.
    const int out_fd =
        options.stdout_fd >= 0 ? options.stdout_fd : open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err_fd =
        options.stderr_fd >= 0 ? options.stderr_fd : open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (chdir(work.c_str()) != 0 || out_fd < 0 || err_fd < 0) _exit(126);
    dup2(out_fd, 1);
    dup2(err_fd, 2);
    if (options.stdin_fd >= 0) dup2(options.stdin_fd, 0);
    if (options.descriptor_3 >= 0) dup2(options.descriptor_3, 3);
    for (int stream = 0; stream <= 2; ++stream)
        if ((options.closed_streams >> stream & 1U) != 0) close(stream);
    if (options.file_size_limit >= 0) {
        const rlimit limit{static_cast<rlim_t>(options.file_size_limit),
                           static_cast<rlim_t>(options.file_size_limit)};
        setrlimit(RLIMIT_FSIZE, &limit);
    }
    if (options.address_space_limit >= 0) {
        const rlimit limit{static_cast<rlim_t>(options.address_space_limit),
                           static_cast<rlim_t>(options.address_space_limit)};
        setrlimit(RLIMIT_AS, &limit);
    }
    if (options.named_temporary) setenv("RAYTRACER_NAMED_TEMPORARY", "1", 1);
    if (options.user != 0 &&
        (setgroups(0, nullptr) != 0 || setgid(options.user) != 0 || setuid(options.user) != 0))
        _exit(125);
    // The signals as a terminal's shell leaves them, whatever this test inherited (nohup
    // ctest, a script's background job): raytracer.exe keeps an ignored one ignored.
    sigset_t interrupts;
    sigemptyset(&interrupts);
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
        sigaddset(&interrupts, signal_number);
        const bool ignored =
            options.ignore_hangup_and_term && (signal_number == SIGHUP || signal_number == SIGTERM);
        signal(signal_number, ignored ? SIG_IGN : SIG_DFL);
    }
    sigprocmask(SIG_UNBLOCK, &interrupts, nullptr);
    execv(argv[0], argv.data());
    _exit(127);
}

// The exit status, or 1000 + the signal that killed it.
int wait_for(pid_t pid) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

int run(const Scratch& folder, const std::vector<std::string>& args, const Options& options = {}) {
    return wait_for(start(folder, args, options));
}

std::string captured_stderr(const Scratch& folder) { return read_bytes(folder.root / "stderr"); }

// Waits until the process catches signal_number (its handler is installed: the SigCgt
// mask of /proc/<pid>/status on Linux), at most 5 s; elsewhere 200 ms.
void wait_until_catching(pid_t pid, int signal_number) {
#ifdef __linux__
    for (int i = 0; i < 1000; ++i) {
        std::ifstream status("/proc/" + std::to_string(pid) + "/status");
        for (std::string line; std::getline(status, line);) {
            if (line.rfind("SigCgt:", 0) != 0) continue;
            const unsigned long long caught = std::stoull(line.substr(7), nullptr, 16);
            if ((caught >> (signal_number - 1) & 1U) != 0) return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
#else
    (void)pid, (void)signal_number;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
#endif
}

bool holds_temporary(const Scratch& folder) {
    for (const fs::directory_entry& e : fs::directory_iterator(folder.work))
        if (e.path().filename().string().rfind(".raytracer-", 0) == 0) return true;
    return false;
}

// Whether the named temporary appears within `tries` looks 5 ms apart.
bool temporary_appears(const Scratch& folder, int tries) {
    bool seen = false;
    for (int i = 0; i < tries && !seen; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        seen = holds_temporary(folder);
    }
    return seen;
}

const std::string kPrecious = "an existing out.ppm that an interrupted run may not touch\n";

}  // namespace

// SIGINT, SIGTERM and SIGHUP mid-render: exit 128 + the signal, one line, nothing left
// (not the unnamed file of Linux, nor the named temporary of other systems, which must
// exist while the render runs for the test to mean anything), out.ppm as it was.
TEST(an_interrupted_render_leaves_nothing_and_exits_128_plus_the_signal) {
    for (const bool named : {false, true}) {
        for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
            const Scratch folder;
            write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
            write_bytes(folder.work / "out.ppm", kPrecious);
            Options options;
            options.named_temporary = named;
            const pid_t pid = start(folder, {"slow.txt"}, options);
            const bool temporary_seen = temporary_appears(folder, 40);
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            CHECK_EQ(temporary_seen, named);  // the unnamed file has no name to see
            kill(pid, signal_number);
            CHECK_EQ(wait_for(pid), 128 + signal_number);
            const std::string name = signal_number == SIGINT    ? "SIGINT"
                                     : signal_number == SIGTERM ? "SIGTERM"
                                                                : "SIGHUP";
            CHECK_EQ(captured_stderr(folder),
                     "raytracer.exe: error: interrupted by " + name + ", no image written\n");
            CHECK_EQ(folder.names(), std::string("out.ppm slow.txt"));
            CHECK_EQ(read_bytes(folder.work / "out.ppm"), kPrecious);
        }
    }
}

// Signals that end a process without a handler of ours (SIGUSR1, SIGALRM; Ctrl-\ and a
// reader of the image gone alike) end it as by default, but leave no named temporary.
TEST(other_ending_signals_leave_no_temporary) {
    for (const int signal_number : {SIGUSR1, SIGALRM}) {
        const Scratch folder;
        write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
        Options options;
        options.named_temporary = true;
        const pid_t pid = start(folder, {"slow.txt"}, options);
        CHECK(temporary_appears(folder, 400));
        kill(pid, signal_number);
        CHECK_EQ(wait_for(pid), 1000 + signal_number);  // ended by the signal itself
        CHECK_EQ(folder.names(), std::string("slow.txt"));
    }
}

// An ending signal that comes while the image is put in place under a named temporary
// (between PendingFile::commit()'s link and rename, or before the rename of a named
// temporary) waits until the rename is done, then ends the run as by default: the image
// is in place and no temporary stays. Here in a child process, with the program's own
// handlers, on commit()'s steps one at a time, so that the signal comes between them.
TEST(an_ending_signal_while_the_image_is_put_in_place_waits_for_it) {
    const Scratch folder;
    write_bytes(folder.work / "out.ppm", kPrecious);
    const std::string work = folder.work.string(), temporary = ".raytracer-0123456789abcdef.tmp";
    const pid_t pid = fork();
    if (pid == 0) {
        rt::install_interrupt_handlers();
        const int dir = open(work.c_str(), O_RDONLY | O_DIRECTORY);
        const int fd = openat(dir, temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
        if (dir < 0 || fd < 0 || write(fd, "new image", 9) != 9 || close(fd) != 0) _exit(2);
        rt::hold_interrupts();
        if (!rt::set_interrupt_cleanup(dir, temporary.c_str())) _exit(3);
        raise(SIGUSR1);  // waits: the temporary is there
        if (faccessat(dir, temporary.c_str(), F_OK, 0) != 0) _exit(4);
        if (renameat(dir, temporary.c_str(), dir, "out.ppm") != 0) _exit(5);
        rt::clear_interrupt_cleanup();  // ends the run, by SIGUSR1
        _exit(6);
    }
    CHECK_EQ(wait_for(pid), 1000 + SIGUSR1);
    CHECK_EQ(read_bytes(folder.work / "out.ppm"), std::string("new image"));
    CHECK_EQ(folder.names(), std::string("out.ppm"));
}

// A reader of standard error gone (2>&1 | head) loses the progress line and the
// messages, not the image nor the exit status: those writes fail (EPIPE) instead of
// ending the run by SIGPIPE.
TEST(a_reader_of_stderr_gone_loses_only_what_goes_there) {
    const Scratch folder;
    write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
    write_bytes(folder.work / "bad.txt", "NEAR 1\n");
    int ends[2] = {-1, -1};
    CHECK_EQ(pipe(ends), 0);
    close(ends[0]);  // nobody reads
    Options options;
    options.stderr_fd = ends[1];
    // One thread: the render outlasts the progress line's first second.
    CHECK_EQ(run(folder, {"--threads", "1", "--progress", "slow.txt"}, options), 0);
    CHECK_EQ(read_bytes(folder.work / "out.ppm").size(), slow_image_bytes());
    CHECK_EQ(run(folder, {"bad.txt"}, options), 1);
    CHECK_EQ(run(folder, {"--threads", "0", "bad.txt"}, options), 2);
    close(ends[1]);
}

// Started with SIGHUP and SIGTERM ignored (nohup, trap '' TERM), the render ignores them
// too and completes; SIGINT, not ignored, still interrupts it.
TEST(signals_ignored_at_start_stay_ignored) {
    const Scratch folder;
    write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
    Options options;
    options.ignore_hangup_and_term = true;
    pid_t pid = start(folder, {"slow.txt"}, options);
    wait_until_catching(pid, SIGINT);  // its handlers are installed: SIGHUP and SIGTERM are not caught
    kill(pid, SIGHUP);
    kill(pid, SIGTERM);
    CHECK_EQ(wait_for(pid), 0);
    CHECK_EQ(captured_stderr(folder), std::string());
    CHECK_EQ(read_bytes(folder.work / "out.ppm").size(), slow_image_bytes());
    pid = start(folder, {"slow.txt", "-o", "second.ppm"}, options);
    wait_until_catching(pid, SIGINT);
    kill(pid, SIGINT);
    CHECK_EQ(wait_for(pid), 128 + SIGINT);
    CHECK_EQ(folder.names(), std::string("out.ppm slow.txt"));
}

// An image going straight to standard output may be partly out when interrupted: the
// message says so rather than "no image written".
TEST(an_interrupted_render_to_standard_output_says_the_image_is_incomplete) {
    const Scratch folder;
    write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
    const pid_t pid = start(folder, {"slow.txt", "-o", "-"});
    for (int i = 0; i < 1000 && read_bytes(folder.root / "stdout").empty(); ++i)  // the image has begun
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    kill(pid, SIGINT);
    CHECK_EQ(wait_for(pid), 128 + SIGINT);
    CHECK_EQ(
        captured_stderr(folder),
        std::string("raytracer.exe: error: interrupted by SIGINT, the image written so far is incomplete\n"));
    CHECK_EQ(folder.names(), std::string("slow.txt"));
}

// Interrupted while the progress line is shown, the run first blanks the line as last
// drawn ("\r", a space for each of its characters, "\r"), then says why it ends, and
// nothing after. Two threads, so that a helper renders while the line is drawn (the
// ThreadSanitizer build checks what they share); the scene 9 times the slow one's
// pixels, so that the line, first drawn after a second, shows on a faster machine too.
TEST(an_interrupt_blanks_the_progress_line_first) {
    const Scratch folder;
    write_bytes(folder.work / "slow.txt", slow_scene("out.ppm", 3 * kSlowRes));
    const pid_t pid = start(folder, {"--threads", "2", "--progress", "slow.txt"});
    for (int i = 0; i < 2000 && captured_stderr(folder).find(" elapsed, ") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    kill(pid, SIGINT);
    CHECK_EQ(wait_for(pid), 128 + SIGINT);
    const std::string shown = captured_stderr(folder);
    const std::string message = "raytracer.exe: error: interrupted by SIGINT, no image written\n";
    CHECK(shown.size() > message.size() && shown.substr(shown.size() - message.size()) == message);
    // Before the message, the pieces between carriage returns: an empty one (the
    // message's own "\r"), the blanks, and before them the last line drawn, if need be
    // past a redraw's own blanks (the signal came between them and its line).
    std::vector<std::string> pieces;
    const std::string before = shown.substr(0, shown.size() - std::min(shown.size(), message.size()));
    for (std::size_t at = 0, next; at <= before.size(); at = next + 1) {
        next = std::min(before.find('\r', at), before.size());
        pieces.push_back(before.substr(at, next - at));
    }
    auto blank = [](const std::string& piece) { return piece.find_first_not_of(' ') == std::string::npos; };
    CHECK(pieces.size() >= 3 && pieces.back().empty());
    if (pieces.size() < 3) return;
    const std::string& blanks = pieces[pieces.size() - 2];
    CHECK(!blanks.empty() && blank(blanks));
    std::size_t line = pieces.size() - 3;
    while (line > 0 && blank(pieces[line])) --line;
    CHECK(pieces[line].find("% of rows, ") != std::string::npos);
    CHECK(blanks.size() >= pieces[line].size());
    CHECK_EQ(folder.names(), std::string("slow.txt"));
}

#ifdef __linux__
// The file is unnamed until complete (O_TMPFILE), so even SIGKILL leaves nothing.
TEST(sigkill_mid_render_leaves_nothing_on_linux) {
    const Scratch folder;
    write_bytes(folder.work / "slow.txt", slow_scene("new.ppm"));
    const pid_t pid = start(folder, {"slow.txt"});
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    kill(pid, SIGKILL);
    CHECK_EQ(wait_for(pid), 1000 + SIGKILL);
    CHECK_EQ(folder.names(), std::string("slow.txt"));
}
#endif

// ulimit -f: a failed write like a full disk (exit 3, its cause), not death by SIGXFSZ.
TEST(a_file_size_limit_is_a_failed_write) {
    for (const bool named : {false, true}) {
        const Scratch folder;
        write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
        write_bytes(folder.work / "out.ppm", kPrecious);
        Options options;
        options.named_temporary = named;
        options.file_size_limit = 4096;  // the image is 30,015 bytes
        CHECK_EQ(run(folder, {"scene.txt"}, options), 3);
        const std::string err = captured_stderr(folder);
        CHECK_EQ(err, std::string(
                          "scene.txt:11: error: OUTPUT 'out.ppm' could not be written in full: the file size "
                          "limit was reached (ulimit -f), expected a writable file path\n"));
        CHECK_EQ(folder.names(), std::string("out.ppm scene.txt"));
        CHECK_EQ(read_bytes(folder.work / "out.ppm"), kPrecious);
    }
}

// A write that fails ends the render: the rows still to come are not drawn, so a full
// disk (here a file-size limit of 4 KiB) does not cost the whole render first. The
// child's CPU time against the same render written in full, in one run.
TEST(a_failed_write_ends_the_render) {
    const Scratch folder;
    write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
    auto cpu_seconds = [&folder](const Options& options, int status) {
        rusage before{}, after{};
        getrusage(RUSAGE_CHILDREN, &before);
        CHECK_EQ(run(folder, {"slow.txt"}, options), status);
        getrusage(RUSAGE_CHILDREN, &after);
        auto seconds = [](const rusage& r) {
            return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
                   static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec) * 1e-6;
        };
        return seconds(after) - seconds(before);
    };
    const double whole = cpu_seconds(Options{}, 0);
    Options limited;
    limited.file_size_limit = 4096;
    const double failed = cpu_seconds(limited, 3);
    std::fprintf(stderr, "CPU time: written in full %.3f s, failed at 4 KiB %.3f s\n", whole, failed);
    CHECK(failed * 4 < whole);
}

// The sanitizers reserve terabytes of address space: no limit can be set under them.
#ifndef RT_SANITIZER_MAPS_TERABYTES
// Memory runs out for 100,000 ellipsoids on a tiny image (the scene is read; the tree
// and its copy of the ellipsoids do not fit): the message names the scene's size, not
// "a smaller RES", and nothing is written.
TEST(out_of_memory_names_the_scene_size) {
    const Scratch folder;
    std::string scene =
        "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES 50 50\nBACK 0 0 0\nAMBIENT 0.2 0.2 0.2\nOUTPUT "
        "oom.ppm\nLIGHT a 0 5 0 1 1 1\n";
    for (int i = 0; i < 100000; ++i)
        scene += "SPHERE s " + std::to_string((i % 200) / 20.0 - 5) +
                 " 0 -10 0.01 0.01 0.01 1 1 1 0.2 0.5 0.5 0.5 10\n";
    write_bytes(folder.work / "oom.txt", scene);
    Options options;
    // Reading takes 36-52 MB of address space (its sphere lists in whole 2 MiB pages, a
    // thread's heap arena), the render 62-72 MB.
    options.address_space_limit = 56L << 20;
    CHECK_EQ(run(folder, {"oom.txt"}, options), 4);
    CHECK_EQ(captured_stderr(folder),
             std::string("raytracer.exe: error: out of memory rendering 'oom.txt' (RES 50 50, "
                         "100000 ellipsoids, 1 light), expected a smaller scene\n"));
    CHECK_EQ(folder.names(), std::string("oom.txt"));
}

// A scene file over the size limit is refused by its size, before any of it is read: in
// 100 MB of address space a file of 100 MB (sparse: it costs no disk) is "too large", not
// "out of memory reading" it; and a line's fields past a statement's are only counted.
TEST(oversized_scene_files_and_lines_are_refused_within_little_memory) {
    const Scratch folder;
    { std::ofstream(folder.work / "huge.txt"); }
    fs::resize_file(folder.work / "huge.txt", std::uintmax_t{100} << 20);
    Options options;
    options.address_space_limit = 100L << 20;
    CHECK_EQ(run(folder, {"huge.txt"}, options), 1);
    CHECK_EQ(captured_stderr(folder),
             std::string("huge.txt: error: is larger than 64 MiB, expected a scene file\n"));

    // A line of ten million fields is counted for its message, not stored field by field.
    std::string line = "SPHERE";
    for (int i = 0; i < 10000000; ++i) line += " 1";
    write_bytes(folder.work / "long_line.txt", line + "\n");
    CHECK_EQ(run(folder, {"long_line.txt"}, options), 1);
    CHECK(captured_stderr(folder).find("SPHERE has 10000000 fields") != std::string::npos);
    // A stream of unknown size is cut off at the limit too, its buffer never grown past
    // it (doubled past it, the buffer took 192 MiB in the copy).
    Options stream_limit;
    stream_limit.address_space_limit = 150L << 20;
    CHECK_EQ(run(folder, {"/dev/zero"}, stream_limit), 1);
    CHECK_EQ(captured_stderr(folder),
             std::string("/dev/zero: error: is larger than 64 MiB, expected a scene file\n"));
    CHECK_EQ(run(folder, {"long_line.txt"}, options), 1);
    CHECK_EQ(captured_stderr(folder),
             std::string("long_line.txt:1: error: SPHERE has 10000000 fields, expected 15: SPHERE <name> "
                         "<pos x> <pos y> <pos z> <scl x> <scl y> <scl z> <r> <g> <b> <Ka> <Kd> <Ks> <Kr> "
                         "<n>\n"));
}
#endif

// A replaced image keeps the permissions of the file it replaces; a new one gets the
// usual 0666 less the umask.
TEST(a_replaced_file_keeps_its_mode) {
    for (const bool named : {false, true}) {
        for (const fs::perms mode :
             {fs::perms::owner_read | fs::perms::owner_write,
              fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read}) {
            const Scratch folder;
            write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
            write_bytes(folder.work / "out.ppm", kPrecious);
            fs::permissions(folder.work / "out.ppm", mode);
            Options options;
            options.named_temporary = named;
            CHECK_EQ(run(folder, {"scene.txt"}, options), 0);
            CHECK(fs::status(folder.work / "out.ppm").permissions() == mode);
            CHECK_EQ(read_bytes(folder.work / "out.ppm").substr(0, 11), std::string("P6\n100 100\n"));
            CHECK_EQ(folder.names(), std::string("out.ppm scene.txt"));
        }
        {  // set-user-ID and set-group-ID are not carried over to the image
            const Scratch folder;
            write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
            write_bytes(folder.work / "out.ppm", kPrecious);
            CHECK_EQ(chmod((folder.work / "out.ppm").c_str(), 06755), 0);
            Options options;
            options.named_temporary = named;
            CHECK_EQ(run(folder, {"scene.txt"}, options), 0);
            CHECK_EQ(static_cast<unsigned>(fs::status(folder.work / "out.ppm").permissions()), 0755U);
        }
        const Scratch folder;
        write_bytes(folder.work / "scene.txt", small_scene("new.ppm"));
        const mode_t mask = umask(0);
        umask(mask);
        Options options;
        options.named_temporary = named;
        CHECK_EQ(run(folder, {"scene.txt"}, options), 0);
        CHECK_EQ(static_cast<unsigned>(fs::status(folder.work / "new.ppm").permissions()), 0666U & ~mask);
    }
}

// An image that could not be put in place is refused before the render, not after it:
// a write-protected file (as a shell's > refuses it), a file in a folder this user may
// not write, another user's file in a folder with the sticky bit (rename() may not
// replace it there), a name longer than the system takes. Run by root (as CI is), as
// another user: root may write anything.
TEST(unreplaceable_outputs_are_refused_before_the_render) {
    const Scratch folder;
    const bool root = geteuid() == 0;
    Options user;
    if (root) {
        user.user = 65534;
        CHECK_EQ(chmod(folder.work.c_str(), 01777), 0);
    }
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    const fs::path out = folder.work / "out.ppm";
    write_bytes(out, kPrecious);
    if (root) CHECK_EQ(chown(out.c_str(), 65534, 65534), 0);
    CHECK_EQ(chmod(out.c_str(), 0444), 0);
    CHECK_EQ(run(folder, {"scene.txt"}, user), 3);
    CHECK(captured_stderr(folder).find("OUTPUT 'out.ppm' is write-protected") != std::string::npos);
    CHECK_EQ(run(folder, {"-o", "out.ppm", "scene.txt"}, user), 3);
    CHECK(captured_stderr(folder).find("-o 'out.ppm' is write-protected") != std::string::npos);
    CHECK_EQ(read_bytes(out), kPrecious);
    // A symbolic link at the name is replaced, not followed: its target's permissions
    // do not count, nor its target's owner in the sticky folder.
    CHECK_EQ(symlink("out.ppm", (folder.work / "linked.ppm").c_str()), 0);
    if (root) CHECK_EQ(lchown((folder.work / "linked.ppm").c_str(), 65534, 65534), 0);
    CHECK_EQ(run(folder, {"-o", "linked.ppm", "scene.txt"}, user), 0);
    CHECK(fs::is_regular_file(fs::symlink_status(folder.work / "linked.ppm")));
    CHECK_EQ(read_bytes(out), kPrecious);
    if (root) {  // root's file, writable by all, in a folder like /tmp
        const fs::path shared = folder.work / "shared.ppm";
        write_bytes(shared, kPrecious);
        CHECK_EQ(chmod(shared.c_str(), 0666), 0);
        CHECK_EQ(run(folder, {"-o", "shared.ppm", "scene.txt"}, user), 3);
        CHECK(
            captured_stderr(folder).find("-o 'shared.ppm' is another user's file in a folder where only its "
                                         "owner may replace it") != std::string::npos);
        CHECK_EQ(read_bytes(shared), kPrecious);
        CHECK_EQ(run(folder, {"-o", "mine.ppm", "scene.txt"}, user), 0);  // a new file is made
        // A file it may write, in a folder it may not: the rename could not put the image there.
        const fs::path closed = folder.work / "closed";
        fs::create_directory(closed);
        write_bytes(closed / "open.ppm", kPrecious);
        CHECK_EQ(chmod((closed / "open.ppm").c_str(), 0666), 0);
        CHECK_EQ(chmod(closed.c_str(), 0555), 0);
        CHECK_EQ(run(folder, {"-o", "closed/open.ppm", "scene.txt"}, user), 3);
        CHECK(captured_stderr(folder).find("-o 'closed/open.ppm' is in a folder this user may not write") !=
              std::string::npos);
        CHECK_EQ(read_bytes(closed / "open.ppm"), kPrecious);
        CHECK_EQ(chmod(closed.c_str(), 0755), 0);
        fs::remove_all(closed);
    }
    CHECK_EQ(run(folder, {"-o", std::string(256, 'a'), "scene.txt"}), 3);
    CHECK(captured_stderr(folder).find("is too long a name or path for the system") != std::string::npos);
    CHECK_EQ(run(folder, {std::string(300, 'x') + ".txt"}), 1);
    CHECK(captured_stderr(folder).find("is too long a name or path for the system, expected a scene file") !=
          std::string::npos);
    CHECK_EQ(folder.names(), std::string(root ? "linked.ppm mine.ppm out.ppm scene.txt shared.ppm"
                                              : "linked.ppm out.ppm scene.txt"));
}

// Run by root (as CI is), a replaced image keeps the owner and group of the file it
// replaces, so that its owner can still read it.
TEST(root_replacing_a_file_keeps_its_owner) {
    if (geteuid() != 0) {
        std::cout << "skip  root_replacing_a_file_keeps_its_owner: not running as root\n";
        return;
    }
    for (const bool named : {false, true}) {
        const Scratch folder;
        write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
        write_bytes(folder.work / "out.ppm", kPrecious);
        CHECK_EQ(chown((folder.work / "out.ppm").c_str(), 65534, 65534), 0);
        CHECK_EQ(chmod((folder.work / "out.ppm").c_str(), 0600), 0);
        Options options;
        options.named_temporary = named;
        CHECK_EQ(run(folder, {"scene.txt"}, options), 0);
        struct stat replaced {};
        CHECK_EQ(stat((folder.work / "out.ppm").c_str(), &replaced), 0);
        CHECK_EQ(replaced.st_uid, uid_t{65534});
        CHECK_EQ(replaced.st_gid, gid_t{65534});
        CHECK_EQ(replaced.st_mode & 07777, mode_t{0600});
        CHECK_EQ(read_bytes(folder.work / "out.ppm").substr(0, 2), std::string("P6"));
    }
}

// A legal name of 240 bytes: the temporary's name must fit the folder's limit too.
TEST(a_240_byte_output_name_works) {
    const std::string name = std::string(236, 'n') + ".ppm";
    for (const bool named : {false, true}) {
        const Scratch folder;
        write_bytes(folder.work / "scene.txt", small_scene(name));
        Options options;
        options.named_temporary = named;
        CHECK_EQ(run(folder, {"scene.txt"}, options), 0);
        CHECK_EQ(captured_stderr(folder), std::string());
        CHECK_EQ(read_bytes(folder.work / name).size(), std::size_t{15 + 30000});
        write_bytes(folder.work / name, kPrecious);  // and replacing it
        CHECK_EQ(run(folder, {"scene.txt"}, options), 0);
        CHECK_EQ(read_bytes(folder.work / name).size(), std::size_t{15 + 30000});
        CHECK_EQ(folder.names(), name + " scene.txt");
    }
}

// A scene may not name a device or FIFO (it would replace it, or block); the user may,
// and the image is written into it.
TEST(devices_and_fifos_only_when_the_user_names_them) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("fifo"));
    CHECK(mkfifo((folder.work / "fifo").c_str(), 0644) == 0);
    CHECK_EQ(run(folder, {"scene.txt"}), 3);
    CHECK(captured_stderr(folder).find("OUTPUT 'fifo' is not a regular file (a device, FIFO or socket)") !=
          std::string::npos);
    CHECK(fs::is_fifo(folder.work / "fifo"));

    CHECK_EQ(run(folder, {"scene.txt", "-o", "/dev/null"}), 0);
    CHECK(fs::is_character_file("/dev/null"));
    CHECK_EQ(run(folder, {"scene.txt", "-o", "image.ppm"}), 0);
    const std::string image = read_bytes(folder.work / "image.ppm");
    const pid_t pid = start(folder, {"scene.txt", "-o", "fifo"});
    CHECK_EQ(read_bytes(folder.work / "fifo"), image);  // opens the FIFO's reading end
    CHECK_EQ(wait_for(pid), 0);
    CHECK(fs::is_fifo(folder.work / "fifo"));
    CHECK_EQ(folder.names(), std::string("fifo image.ppm scene.txt"));

#ifndef RT_UNDER_TSAN  // which holds a signal until the thread leaves its system call, here never
    // Interrupted while it waits for a reader, nothing of the image is out yet.
    const pid_t waiting = start(folder, {"scene.txt", "-o", "fifo"});
    wait_until_catching(waiting, SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    kill(waiting, SIGINT);
    CHECK_EQ(wait_for(waiting), 128 + SIGINT);
    CHECK_EQ(captured_stderr(folder),
             std::string("raytracer.exe: error: interrupted by SIGINT, no image written\n"));
#endif
}

// The scene file under another name is still the scene file: device and inode decide.
TEST(output_naming_the_scene_through_a_link_is_refused) {
    const Scratch folder;
    const std::string scene = small_scene("hard.ppm");
    write_bytes(folder.work / "scene.txt", scene);
    fs::create_hard_link(folder.work / "scene.txt", folder.work / "hard.ppm");
    CHECK_EQ(run(folder, {"scene.txt"}), 3);
    CHECK(captured_stderr(folder).find("OUTPUT 'hard.ppm' is the scene file itself") != std::string::npos);
    fs::create_symlink("scene.txt", folder.work / "soft.ppm");
    CHECK_EQ(run(folder, {"scene.txt", "-o", "soft.ppm"}), 3);
    CHECK(captured_stderr(folder).find("-o 'soft.ppm' is the scene file itself") != std::string::npos);
    CHECK_EQ(read_bytes(folder.work / "scene.txt"), scene);
}

// A path that cannot be followed (a loop of symbolic links) is said to be so, not to be
// missing: as a scene file, and as the folder of an output.
TEST(a_loop_of_symbolic_links_is_not_called_missing) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    fs::create_symlink("loop", folder.work / "loop");
    CHECK_EQ(run(folder, {"loop"}), 1);
    std::string err = captured_stderr(folder);
    CHECK(err.find("does not exist") == std::string::npos);
    CHECK(err.find("loop: error: cannot be opened for reading: " + std::string(std::strerror(ELOOP))) !=
          std::string::npos);
    CHECK_EQ(run(folder, {"scene.txt", "-o", "loop/out.ppm"}), 3);
    err = captured_stderr(folder);
    CHECK(err.find("does not exist") == std::string::npos);
    CHECK(err.find("its folder 'loop' cannot be reached") != std::string::npos);
    // A scene's OUTPUT there: where the way cannot be followed, it is not known to stay in
    // the working folder, and is refused as such.
    write_bytes(folder.work / "scene.txt", small_scene("loop/out.ppm"));
    CHECK_EQ(run(folder, {"scene.txt"}), 3);
    CHECK(captured_stderr(folder).find(
              "OUTPUT 'loop/out.ppm' cannot be checked to stay in the working folder (" +
              std::string(std::strerror(ELOOP)) + ")") != std::string::npos);
}

// -o - > both.ppm 2>&1 --progress: the progress line would go into the image, so it is
// refused before the render; without --progress nothing goes to stderr and the image is
// whole.
TEST(a_progress_line_into_the_image_is_refused) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    Options options;
    options.stdout_fd = options.stderr_fd =
        open((folder.work / "both.ppm").c_str(), O_WRONLY | O_CREAT, 0644);
    CHECK(options.stdout_fd >= 0);
    CHECK_EQ(run(folder, {"--progress", "-o", "-", "scene.txt"}, options), 3);
    CHECK_EQ(read_bytes(folder.work / "both.ppm"),
             std::string("raytracer.exe: error: -o '-' is also standard error, where --progress draws "
                         "its line, expected another file for the image\n"));
    CHECK(ftruncate(options.stdout_fd, 0) == 0 && lseek(options.stdout_fd, 0, SEEK_SET) == 0);
    CHECK_EQ(run(folder, {"-o", "-", "scene.txt"}, options), 0);
    close(options.stdout_fd);
    CHECK_EQ(read_bytes(folder.work / "both.ppm").substr(0, 3), std::string("P6\n"));
    CHECK_EQ(read_bytes(folder.work / "both.ppm").size(), std::size_t{30015});  // 100x100
    // 2>&1 | ...: one pipe.
    int pipe_fds[2];
    CHECK_EQ(pipe(pipe_fds), 0);
    options.stdout_fd = options.stderr_fd = pipe_fds[1];
    CHECK_EQ(run(folder, {"--progress", "-o", "-", "scene.txt"}, options), 3);
    close(pipe_fds[1]);
    char said[512] = {};
    CHECK(read(pipe_fds[0], said, sizeof said - 1) > 0);
    close(pipe_fds[0]);
    CHECK(std::string(said).find("is also standard error, where --progress draws its line") !=
          std::string::npos);
}

// The pipe a scene comes in on is not written: this process holds its reading end, so
// an image larger than the pipe would block it for good (-o /dev/stdin, /dev/fd/0).
TEST(the_pipe_of_standard_input_is_not_an_output) {
    for (const char* name : {"/dev/stdin", "/dev/fd/0"}) {
        const Scratch folder;
        int input[2];
        CHECK_EQ(pipe(input), 0);
        const std::string scene = small_scene("out.ppm");
        CHECK_EQ(write(input[1], scene.data(), scene.size()), static_cast<ssize_t>(scene.size()));
        close(input[1]);
        Options options;
        options.stdin_fd = input[0];
        CHECK_EQ(run(folder, {"-", "-o", name}, options), 3);
        close(input[0]);
        CHECK(captured_stderr(folder).find(std::string("-o '") + name +
                                           "' is standard input, which is read, expected another file") !=
              std::string::npos);
    }
}

// --help and --version into a full disk (or a closed stdout): exit 3 and one line, not a
// silent success.
TEST(help_that_cannot_be_written_is_an_error) {
    const Scratch folder;
    for (const char* option : {"--help", "--version"}) {
        Options options;
        options.stdout_fd = open("/dev/full", O_WRONLY);
        CHECK(options.stdout_fd >= 0);
        CHECK_EQ(run(folder, {option}, options), 3);
        close(options.stdout_fd);
        CHECK(captured_stderr(folder).rfind("raytracer.exe: error: standard output could not be written: ",
                                            0) == 0);
    }
}

// raytracer.exe -o - scene.txt >> scene.txt: standard output is the scene file itself,
// refused before anything is written to it; so too where the scene is standard input.
TEST(standard_output_into_the_scene_file_is_refused) {
    const Scratch folder;
    const std::string scene = small_scene("out.ppm");
    write_bytes(folder.work / "scene.txt", scene);
    Options options;
    options.stdout_fd = open((folder.work / "scene.txt").c_str(), O_WRONLY | O_APPEND);
    CHECK(options.stdout_fd >= 0);
    CHECK_EQ(run(folder, {"-o", "-", "scene.txt"}, options), 3);
    const std::string refused =
        "raytracer.exe: error: -o - (standard output) is the scene file itself, expected another file "
        "for the image\n";
    CHECK_EQ(captured_stderr(folder), refused);
    // raytracer.exe - -o - < scene.txt >> scene.txt: the scene read from standard input.
    options.stdin_fd = open((folder.work / "scene.txt").c_str(), O_RDONLY);
    CHECK(options.stdin_fd >= 0);
    CHECK_EQ(run(folder, {"-", "-o", "-"}, options), 3);
    CHECK_EQ(captured_stderr(folder), refused);
    close(options.stdin_fd), close(options.stdout_fd);
    CHECK_EQ(read_bytes(folder.work / "scene.txt"), scene);
    Options closed;  // raytracer.exe - <&-
    closed.closed_streams = 1;
    CHECK_EQ(run(folder, {"-"}, closed), 1);
    CHECK_EQ(captured_stderr(folder),
             std::string("<stdin>: error: is closed (or a folder), expected a scene file\n"));
}

// A folder on the way that is a symbolic link out of the working folder is outside it.
TEST(a_symbolic_link_out_of_the_working_folder_is_outside_it) {
    const Scratch folder;
    fs::create_directories(folder.root / "elsewhere");
    fs::create_directory_symlink(folder.root / "elsewhere", folder.work / "escape");
    fs::create_directories(folder.work / "inside");
    fs::create_directory_symlink("inside", folder.work / "alias");
    write_bytes(folder.work / "scene.txt", small_scene("escape/out.ppm"));
    CHECK_EQ(run(folder, {"scene.txt"}), 3);
    CHECK(captured_stderr(folder).find(
              "OUTPUT 'escape/out.ppm' leaves the working folder through a symbolic link") !=
          std::string::npos);
    CHECK(fs::is_empty(folder.root / "elsewhere"));
    CHECK_EQ(run(folder, {"scene.txt", "-o", "escape/out.ppm"}), 0);  // the user may
    CHECK(fs::exists(folder.root / "elsewhere" / "out.ppm"));
    write_bytes(folder.work / "scene.txt", small_scene("alias/out.ppm"));  // a link that stays inside
    CHECK_EQ(run(folder, {"scene.txt"}), 0);
    CHECK(fs::exists(folder.work / "inside" / "out.ppm"));
}

// A working folder deleted before the image's file is made (the scene still coming on
// standard input) is said to be deleted, not unwritable: exit 3, in both modes.
TEST(a_deleted_working_folder_is_named_as_such) {
    for (const bool named : {false, true}) {
        const Scratch folder;
        int scene_pipe[2];
        CHECK(pipe2(scene_pipe, O_CLOEXEC) == 0);  // the write end not inherited: an end of file
        Options options;
        options.named_temporary = named;
        options.stdin_fd = scene_pipe[0];
        const pid_t pid = start(folder, {"-"}, options);
        close(scene_pipe[0]);
        wait_until_catching(pid, SIGINT);  // running in folder.work
        fs::remove(folder.work);
        const std::string scene = small_scene("out.ppm");
        CHECK_EQ(write(scene_pipe[1], scene.data(), scene.size()), static_cast<ssize_t>(scene.size()));
        close(scene_pipe[1]);
        CHECK_EQ(wait_for(pid), 3);
        CHECK(captured_stderr(folder).find(
                  "OUTPUT 'out.ppm' cannot be created: its folder '.' has been deleted") !=
              std::string::npos);
    }
}

// Whether process pid holds a file open in folder (a link of /proc/<pid>/fd there: the
// unnamed file of Linux shows as "folder/#inode (deleted)") within `tries` looks 5 ms apart.
bool opens_a_file_in(pid_t pid, const fs::path& folder, int tries) {
    const std::string prefix = folder.string() + "/";
    for (int i = 0; i < tries; ++i) {
        std::error_code ec;
        for (const fs::directory_entry& fd :
             fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec))
            if (fs::read_symlink(fd.path(), ec).string().rfind(prefix, 0) == 0) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
}

// The OUTPUT's folder replaced mid-render by a link out of the working folder does not
// move the image: it goes into the folder that was checked, under its new name, by the
// descriptor held since, and nothing goes out (the unnamed file and the named temporary
// alike). The render is stopped while the folder is swapped, before the image is put in
// place.
TEST(a_folder_swapped_for_a_link_out_mid_render_keeps_the_image_inside) {
    for (const bool named : {false, true}) {
        const Scratch folder;
        fs::create_directories(folder.work / "sub");
        fs::create_directories(folder.root / "elsewhere");
        write_bytes(folder.work / "slow.txt", slow_scene("sub/out.ppm"));
        Options options;
        options.named_temporary = named;
        const pid_t pid = start(folder, {"slow.txt"}, options);
        CHECK(opens_a_file_in(pid, folder.work / "sub", 1000));
        kill(pid, SIGSTOP);
        CHECK(!fs::exists(folder.work / "sub" / "out.ppm"));  // not yet in place
        fs::rename(folder.work / "sub", folder.work / "checked");
        fs::create_directory_symlink(folder.root / "elsewhere", folder.work / "sub");
        kill(pid, SIGCONT);
        CHECK_EQ(wait_for(pid), 0);
        CHECK(fs::is_empty(folder.root / "elsewhere"));
        CHECK_EQ(fs::file_size(folder.work / "checked" / "out.ppm"), slow_image_bytes());
        CHECK_EQ(folder.names(), std::string("checked slow.txt sub"));
    }
}

// Folders dd/dd/... `levels` deep below the folder `top` holds open, made one at a time
// by handle: their path may be longer than PATH_MAX, which calls by path refuse. Removed
// with all they hold, deepest first, when it goes (fs::remove_all() cannot reach them).
class DeepFolders {
public:
    DeepFolders(int top, int levels) {
        fds_.push_back(dup(top));
        for (int i = 0; i < levels; ++i) {
            CHECK(mkdirat(fds_.back(), "dd", 0755) == 0);
            fds_.push_back(openat(fds_.back(), "dd", O_RDONLY | O_DIRECTORY | O_CLOEXEC));
            CHECK(fds_.back() >= 0);
        }
    }
    DeepFolders(const DeepFolders&) = delete;
    DeepFolders& operator=(const DeepFolders&) = delete;
    ~DeepFolders() {
        for (std::size_t i = fds_.size() - 1; i > 0; --i) {
            remove_files(fds_[i]);
            close(fds_[i]);
            unlinkat(fds_[i - 1], "dd", AT_REMOVEDIR);
        }
        close(fds_[0]);
    }
    int at(int level) const { return fds_[static_cast<std::size_t>(level)]; }

private:
    static void remove_files(int folder) {
        DIR* entries = fdopendir(dup(folder));
        if (entries == nullptr) return;
        while (const dirent* e = readdir(entries))
            if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0)
                unlinkat(folder, e->d_name, 0);  // a folder (dd) stays: unlinkat() without AT_REMOVEDIR
        closedir(entries);
    }
    std::vector<int> fds_;
};

// The way out is found by following the links, not by resolving the whole path: through
// a link whose resolved path is longer than PATH_MAX (where fs::canonical() fails), the
// scene is still refused, and nothing is written there.
TEST(a_symbolic_link_out_is_found_however_long_its_resolved_path) {
    const Scratch folder;
    fs::create_directories(folder.root / "elsewhere");
    const int elsewhere = open((folder.root / "elsewhere").c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    CHECK(elsewhere >= 0);
    {
        const DeepFolders deep(elsewhere, 1500);
        std::string middle = (folder.root / "elsewhere").string(), rest;  // 1000 levels, and 500 more
        for (int i = 0; i < 1000; ++i) middle += "/dd";
        for (int i = 0; i < 500; ++i) rest += "dd/";
        CHECK(symlinkat(rest.c_str(), deep.at(1000), "more") == 0);  // 1500 levels: over 4500 bytes
        fs::create_directory_symlink(middle + "/more", folder.work / "far");
        CHECK(middle.size() + 4 + rest.size() > PATH_MAX);
        write_bytes(folder.work / "scene.txt", small_scene("far/out.ppm"));
        CHECK_EQ(run(folder, {"scene.txt"}), 3);
        CHECK(
            captured_stderr(folder).find("OUTPUT 'far/out.ppm' leaves the working folder through a symbolic "
                                         "link") != std::string::npos);
        CHECK(faccessat(deep.at(1500), "out.ppm", F_OK, 0) != 0);
    }
    close(elsewhere);
}

// A pseudo-terminal: the program is given `terminal`, the test reads what it shows from
// `master`.
struct PseudoTerminal {
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    int terminal = -1;

    PseudoTerminal() {
        CHECK(master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0);
        terminal = open(ptsname(master), O_RDWR | O_NOCTTY);
        CHECK(terminal >= 0);
    }
    PseudoTerminal(const PseudoTerminal&) = delete;
    PseudoTerminal& operator=(const PseudoTerminal&) = delete;
    // Once the program alone holds it, reading `master` ends when the program does.
    void close_terminal() { close(std::exchange(terminal, -1)); }
    ~PseudoTerminal() {
        if (terminal >= 0) close(terminal);
        if (master >= 0) close(master);
    }
};

// What a render of the slow scene on one thread shows on a pseudo-terminal of this many
// columns (0: the size left unset), read until the render ends.
std::string progress_on_terminal(const Scratch& folder, unsigned short columns) {
    PseudoTerminal pty;
    if (columns > 0) {
        winsize size{};
        size.ws_col = columns, size.ws_row = 24;
        CHECK_EQ(ioctl(pty.terminal, TIOCSWINSZ, &size), 0);
    }
    Options options;
    options.stderr_fd = pty.terminal;
    // One thread, so that the render takes seconds even on a faster machine.
    const pid_t pid = start(folder, {"--threads", "1", "slow.txt"}, options);
    pty.close_terminal();
    std::string shown;
    char buffer[4096];
    for (ssize_t got; (got = read(pty.master, buffer, sizeof buffer)) > 0;)
        shown.append(buffer, static_cast<std::size_t>(got));
    CHECK_EQ(wait_for(pid), 0);
    CHECK_EQ(read_bytes(folder.work / "out.ppm").size(), slow_image_bytes());
    return shown;
}

// Runs raytracer.exe with args, descriptor `stream` (1 or 3) on a pseudo-terminal drained
// meanwhile (were the image written there, the run would end with 0 rather than block on
// a full terminal): the exit status.
int run_on_terminal(const Scratch& folder, const std::vector<std::string>& args, int stream) {
    const PseudoTerminal pty;
    CHECK_EQ(fcntl(pty.master, F_SETFL, O_NONBLOCK), 0);
    Options on_terminal;
    (stream == 1 ? on_terminal.stdout_fd : on_terminal.descriptor_3) = pty.terminal;
    const pid_t pid = start(folder, args, on_terminal);
    char buffer[4096];
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        while (read(pty.master, buffer, sizeof buffer) > 0) {
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

// -o - with standard output on a terminal is refused: a binary image would garble it
// (a device the user names with -o, a serial line too, is written into as asked).
TEST(standard_output_on_a_terminal_is_refused) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    CHECK_EQ(run_on_terminal(folder, {"-o", "-", "scene.txt"}, 1), 3);
    CHECK(captured_stderr(folder).find("-o '-' is a terminal, expected a pipe or a file") !=
          std::string::npos);
}

// raytracer.exe - on a terminal: the scene typed there ends at one Ctrl-D, as for cat,
// and -o naming that terminal writes the image there (it is not "the scene file").
TEST(a_scene_typed_on_a_terminal_ends_at_one_end_of_file) {
    const Scratch folder;
    const PseudoTerminal pty;
    CHECK_EQ(fcntl(pty.master, F_SETFL, O_NONBLOCK), 0);
    Options typed;
    typed.stdin_fd = pty.terminal;
    const pid_t pid = start(folder, {"-", "-o", ptsname(pty.master)}, typed);
    const std::string scene = small_scene("out.ppm") + "\x04";  // VEOF, Ctrl-D: end of input
    CHECK_EQ(write(pty.master, scene.data(), scene.size()), static_cast<ssize_t>(scene.size()));
    int status = 0;
    char buffer[4096];
    std::size_t shown = 0;  // the echo, then the image
    for (int ms = 0; ms < 20000 && waitpid(pid, &status, WNOHANG) == 0; ++ms) {
        for (ssize_t got; (got = read(pty.master, buffer, sizeof buffer)) > 0;)
            shown += static_cast<std::size_t>(got);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (waitpid(pid, &status, WNOHANG) == 0) {  // still reading: ended here, and failed
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
    }
    for (ssize_t got; (got = read(pty.master, buffer, sizeof buffer)) > 0;)
        shown += static_cast<std::size_t>(got);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    CHECK_EQ(captured_stderr(folder), std::string());
    CHECK(shown > std::size_t{30000});  // the 100x100 image went to the terminal
}

// On a terminal, a render past a second shows one line kept up to date, erased at the
// end: no newline at all, and never wider than the terminal (a wider one would wrap and
// leave its start behind).
TEST(a_long_render_shows_progress_on_a_terminal_only) {
    const Scratch folder;
    write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
    std::string shown = progress_on_terminal(folder, 0);
    if (shown.find("% of rows, ") == std::string::npos) std::cout << "on the terminal: '" << shown << "'\n";
    CHECK(shown.find("% of rows, ") != std::string::npos);
    CHECK(shown.find(" elapsed, about ") != std::string::npos);
    CHECK(shown.find('\n') == std::string::npos);
    CHECK(shown.size() > 2 && shown.substr(shown.size() - 2) == " \r");  // erased: blanks, back to the start

    shown = progress_on_terminal(folder, 30);
    CHECK(shown.find("raytracer.exe: ") != std::string::npos);
    std::size_t widest = 0;
    for (std::size_t at = 0, next; at < shown.size(); at = next + 1) {
        next = std::min(shown.find('\r', at), shown.size());
        widest = std::max(widest, next - at);
    }
    CHECK_EQ(widest, std::size_t{29});
    CHECK(shown.find('\n') == std::string::npos);

    // Not a terminal (a grader's pipe or file): nothing, unless --progress forces it.
    CHECK_EQ(run(folder, {"--threads", "1", "slow.txt"}), 0);
    CHECK_EQ(captured_stderr(folder), std::string());
    const std::string image = read_bytes(folder.work / "out.ppm");
    CHECK_EQ(run(folder, {"--threads=1", "--progress", "slow.txt"}), 0);
    CHECK(captured_stderr(folder).find("% of rows, ") != std::string::npos);

    // Started with standard error closed, the image must not take its number and receive
    // the progress line.
    Options closed;
    closed.closed_streams = 4;
    fs::remove(folder.work / "out.ppm");
    CHECK_EQ(run(folder, {"--threads=1", "--progress", "slow.txt"}, closed), 0);
    CHECK(read_bytes(folder.work / "out.ppm") == image);
}

// On the reference path a row of a large scene takes seconds; the line is drawn while
// the row renders, not only at its end. Here the image is one row of about 3 s (110 ms a
// pixel, on one thread): a line drawn at rows' ends alone never shows. The render is
// interrupted once the line is seen.
TEST(a_long_row_shows_progress_while_it_renders) {
    const Scratch folder;
    std::minstd_rand random(5);
    auto u = [&random](double lo, double hi) {
        return std::to_string(lo + (hi - lo) * static_cast<double>(random()) /
                                       static_cast<double>(std::minstd_rand::max()));
    };
    // A wall in front of every eye ray, 3,000 lights before it and 2,000 spheres behind
    // it: each shadow ray is tried against every ellipsoid and blocked by none.
    std::string text =
        "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES 32 1\nBACK 0 0 0\nAMBIENT 0.1 0.1 0.1\n"
        "OUTPUT out.ppm\nSPHERE wall 0 0 -10 100 100 1 0.5 0.5 0.5 0.1 0.5 0.5 0 10\n";
    for (int i = 0; i < 2000; ++i)
        text += "SPHERE s" + std::to_string(i) + " " + u(-50, 50) + " " + u(-50, 50) +
                " -30 0.1 0.1 0.1 0.5 0.5 0.5 0.1 0.5 0.5 0 10\n";
    for (int i = 0; i < 3000; ++i)
        text +=
            "LIGHT l" + std::to_string(i) + " " + u(-5, 5) + " " + u(-5, 5) + " -5 0.0003 0.0003 0.0003\n";
    write_bytes(folder.work / "row.txt", text);
    PseudoTerminal pty;
    Options options;
    options.stderr_fd = pty.terminal;
    const auto started = std::chrono::steady_clock::now();
    const pid_t pid = start(folder, {"--reference", "--threads", "1", "row.txt"}, options);
    pty.close_terminal();
    std::string shown;
    char buffer[4096];
    // Until the line shows, or the program ends (then reading fails).
    for (ssize_t got; shown.find("% of rows, ") == std::string::npos &&
                      (got = read(pty.master, buffer, sizeof buffer)) > 0;)
        shown.append(buffer, static_cast<std::size_t>(got));
    const std::chrono::duration<double> seen_after = std::chrono::steady_clock::now() - started;
    kill(pid, SIGINT);
    const int status = wait_for(pid);
    CHECK(status == 130 || status == 0);  // 0: it ended first
    if (shown.find("  0% of rows, ") == std::string::npos) std::cout << "shown: '" << shown << "'\n";
    CHECK(shown.find("  0% of rows, ") != std::string::npos);  // before its one row ended
    CHECK(seen_after.count() >= 1.0);  // nothing before a second (ProgressSink::kFirstAfter)
}

// -o naming the file standard output goes to (/dev/stdout, /dev/fd/1, /proc/self/fd/1)
// writes the image there, as -o - does, instead of replacing the link; standard error,
// where the messages go, is refused.
TEST(o_naming_standard_output_writes_to_it) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    CHECK_EQ(run(folder, {"scene.txt"}), 0);
    const std::string image = read_bytes(folder.work / "out.ppm");
    CHECK(image.size() > 17);
    for (const char* path : {"/proc/self/fd/1", "/dev/fd/1"}) {
        if (!fs::exists(path)) continue;
        Options options;
        options.stdout_fd = open((folder.work / "image.ppm").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        CHECK(options.stdout_fd >= 0);
        CHECK_EQ(run(folder, {"-o", path, "scene.txt"}, options), 0);
        close(options.stdout_fd);
        CHECK_EQ(captured_stderr(folder), std::string());
        CHECK(read_bytes(folder.work / "image.ppm") == image);
    }
    if (fs::exists("/proc/self/fd/2")) {
        CHECK_EQ(run(folder, {"-o", "/proc/self/fd/2", "scene.txt"}), 3);
        CHECK_EQ(captured_stderr(folder),
                 std::string("raytracer.exe: error: -o '/proc/self/fd/2' is standard "
                             "error, where the messages go, expected another file for "
                             "the image\n"));
        Options reading;  // standard input from a regular file: not replaced either
        write_bytes(folder.work / "input.txt", kPrecious);
        reading.stdin_fd = open((folder.work / "input.txt").c_str(), O_RDONLY);
        CHECK_EQ(run(folder, {"-o", "/proc/self/fd/0", "scene.txt"}, reading), 3);
        CHECK(captured_stderr(folder).find("is standard input, which is read") != std::string::npos);
        write_bytes(folder.work / "to_input.txt", small_scene("input.txt"));  // a scene's OUTPUT too
        CHECK_EQ(run(folder, {"to_input.txt"}, reading), 3);
        CHECK(captured_stderr(folder).find("OUTPUT 'input.txt' is standard input") != std::string::npos);
        close(reading.stdin_fd);
        CHECK_EQ(read_bytes(folder.work / "input.txt"), kPrecious);
    }
    // A device that standard input and error also are is written into as usual.
    Options null_streams;
    null_streams.stdin_fd = open("/dev/null", O_RDONLY);
    null_streams.stderr_fd = open("/dev/null", O_WRONLY);
    CHECK_EQ(run(folder, {"-o", "/dev/null", "scene.txt"}, null_streams), 0);
    close(null_streams.stdin_fd), close(null_streams.stderr_fd);
    // -o - with standard output closed: an error, not an image sent nowhere.
    Options closed;
    closed.closed_streams = 2;
    CHECK_EQ(run(folder, {"-o", "-", "scene.txt"}, closed), 3);
    CHECK(captured_stderr(folder).find(
              "-o - (standard output) is closed (or a folder), expected a pipe or a file") !=
          std::string::npos);
    if (fs::exists("/dev/stdout")) {  // by its name too, not "is a folder"
        CHECK_EQ(run(folder, {"-o", "/dev/stdout", "scene.txt"}, closed), 3);
        CHECK(captured_stderr(folder).find("-o '/dev/stdout' is standard output, which is closed") !=
              std::string::npos);
    }
    if (fs::exists("/dev/fd/0")) {  // standard input and error alike
        for (const auto& [stream, name] : {std::pair<unsigned, const char*>{0, "input"}, {2, "error"}}) {
            Options closed_stream;
            closed_stream.closed_streams = 1U << stream;
            const std::string path = "/dev/fd/" + std::to_string(stream);
            CHECK_EQ(run(folder, {"-o", path, "scene.txt"}, closed_stream), 3);
            if (stream != 2)
                CHECK(captured_stderr(folder).find("-o '" + path + "' is standard " + name +
                                                   ", which is closed") != std::string::npos);
        }
    }
}

// -o /dev/fd/N: a descriptor the shell opened (3> f.ppm, 3>> f.ppm) is written into as
// it is open, not replaced (a link that /proc makes: replacing it failed as "cannot be
// created"); one open for reading only, or one not open, is refused before the render.
TEST(o_naming_another_descriptor_writes_into_it) {
#ifdef __linux__
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    CHECK_EQ(run(folder, {"scene.txt"}), 0);
    const std::string image = read_bytes(folder.work / "out.ppm");
    const fs::path target = folder.work / "descriptor.ppm";
    for (const bool append : {false, true}) {
        write_bytes(target, "HEAD");
        Options options;
        options.descriptor_3 = open(target.c_str(), O_WRONLY | (append ? O_APPEND : O_TRUNC));
        CHECK(options.descriptor_3 >= 0);
        CHECK_EQ(run(folder, {"-o", "/dev/fd/3", "scene.txt"}, options), 0);
        close(options.descriptor_3);
        CHECK_EQ(captured_stderr(folder), std::string());
        CHECK(read_bytes(target) == (append ? "HEAD" + image : image));
    }
    Options reading;
    reading.descriptor_3 = open(target.c_str(), O_RDONLY);
    CHECK(reading.descriptor_3 >= 0);
    CHECK_EQ(run(folder, {"-o", "/proc/self/fd/3", "scene.txt"}, reading), 3);
    close(reading.descriptor_3);
    CHECK_EQ(captured_stderr(folder),
             std::string("raytracer.exe: error: -o '/proc/self/fd/3' is descriptor 3, which is open for "
                         "reading only, expected one open for writing (3> file)\n"));
    CHECK_EQ(run(folder, {"-o", "/dev/fd/200", "scene.txt"}), 3);
    CHECK(captured_stderr(folder).find("'/dev/fd/200' is descriptor 200, which is not open") !=
          std::string::npos);
    CHECK(read_bytes(target) == "HEAD" + image);
    // A terminal is refused, as for -o -.
    CHECK_EQ(run_on_terminal(folder, {"-o", "/dev/fd/3", "scene.txt"}, 3), 3);
    CHECK(captured_stderr(folder).find("is descriptor 3, which is a terminal") != std::string::npos);
    // With --progress, standard error itself (a pipe: 3>&2) is refused: the line would go
    // into the image.
    int messages[2];
    CHECK_EQ(pipe(messages), 0);
    Options progress;
    progress.stderr_fd = progress.descriptor_3 = messages[1];
    CHECK_EQ(run(folder, {"--progress", "-o", "/dev/fd/3", "scene.txt"}, progress), 3);
    close(messages[1]);
    std::string said;
    char buffer[4096];
    for (ssize_t got; (got = read(messages[0], buffer, sizeof buffer)) > 0;)
        said.append(buffer, static_cast<std::size_t>(got));
    close(messages[0]);
    CHECK(said.find("-o '/dev/fd/3' is also standard error, where --progress draws its line") !=
          std::string::npos);
#endif
}

// A reader that stops reading (a pager, a slow converter) holds the render up, and the
// render's threads then sleep (threads that yielded in a loop instead kept a core busy
// each but the writer's: 3.6 s of CPU in 4 s held up, on two threads).
TEST(threads_held_up_by_a_slow_reader_sleep) {
    const Scratch folder;
    // 1000x1000: 3 MB of image, far beyond a pipe's buffer, rendered in milliseconds.
    std::string scene = small_scene("out.ppm");
    scene.replace(scene.find("RES 100 100"), 11, "RES 1000 1000");
    write_bytes(folder.work / "scene.txt", scene);
    int pipe_ends[2];
    CHECK_EQ(pipe(pipe_ends), 0);
    Options options;
    options.stdout_fd = pipe_ends[1];
    const pid_t pid = start(folder, {"--threads", "3", "-o", "-", "scene.txt"}, options);
    close(pipe_ends[1]);
    const double held_seconds = 1.5;
    std::this_thread::sleep_for(std::chrono::duration<double>(held_seconds));
    std::size_t read_total = 0;
    char buffer[1 << 16];
    for (ssize_t got; (got = read(pipe_ends[0], buffer, sizeof buffer)) != 0;) {
        if (got < 0 && errno != EINTR) break;
        if (got > 0) read_total += static_cast<std::size_t>(got);
    }
    close(pipe_ends[0]);
    int status = 0;
    rusage usage{};
    while (wait4(pid, &status, 0, &usage) < 0) {
    }
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    const std::size_t image_bytes = 17 + std::size_t{1000} * 1000 * 3;  // "P6\n1000 1000\n255\n", pixels
    CHECK_EQ(read_total, image_bytes);
    const double cpu = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    if (cpu >= held_seconds / 4)
        std::cout << "CPU time while held up " << held_seconds << " s: " << cpu << " s\n";
    CHECK(cpu < held_seconds / 4);
}

// A signal that arrives once the image is being put in place (PendingFile::commit()),
// or once the last of it has gone to a stream, is ignored: its handler would otherwise
// say "no image written" or "incomplete" of a complete image. Here in this process, with
// the program's own handlers: each SIGTERM raised below must return (were it not
// ignored, this process would end with status 143).
TEST(an_interrupt_once_the_image_is_out_is_ignored) {
    const Scratch folder;
    rt::install_interrupt_handlers();
    rt::PendingFile file((folder.work / "image.ppm").c_str());
    CHECK_EQ(file.error(), std::string());
    file.write("P6\n1 1\n255\n\0\0\0", 14);
    CHECK_EQ(file.commit(), std::string());
    CHECK_EQ(std::raise(SIGTERM), 0);
    CHECK_EQ(read_bytes(folder.work / "image.ppm").size(), std::size_t{14});

    rt::release_interrupts();  // armed again, for a stream this time
    rt::PendingFile stream("/dev/null", rt::Destination::WriteInto);
    CHECK_EQ(stream.error(), std::string());
    stream.expect_size(14);
    stream.write("P6\n1 1\n255\n", 11);
    stream.write("\0\0\0", 3);  // the last bytes are out
    CHECK_EQ(std::raise(SIGTERM), 0);
    CHECK_EQ(stream.commit(), std::string());
}
