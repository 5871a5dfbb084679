// raytracer-grade's processes and files (POSIX): stopped by SIGTERM or SIGINT while a
// render hangs, or by its report's reader going away (SIGPIPE), the grader ends by that
// signal, the render it started is killed and reaped, and the grader's scratch folder is
// gone from the temporary directory; a report it cannot write or a temporary folder it
// cannot use is exit status 3; what a render leaves running is stopped with it.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>

#include "../check.h"

namespace fs = std::filesystem;

namespace {

// Waits up to 20 s for the file or the process; false on a timeout.
bool wait_for_file(const fs::path& file) {
    for (int i = 0; i < 2000 && !fs::exists(file); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return fs::exists(file);
}

bool wait_for_exit(pid_t pid, int& status) {
    for (int i = 0; i < 2000; ++i) {
        if (waitpid(pid, &status, WNOHANG) == pid) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

// A folder of this test's own, removed at the end.
struct Root {
    fs::path path =
        fs::temp_directory_path() / ("raytracer-grade-test-" + std::to_string(std::random_device{}()));
    Root() { fs::create_directories(path / "tmp"); }
    ~Root() { fs::remove_all(path); }
};

void interrupt_a_hanging_render(int signal) {
    const Root root;
    const fs::path temporary = root.path / "tmp", pid_file = root.path / "render.pid";

    const pid_t grader = fork();
    if (grader == 0) {
        setenv("TMPDIR", temporary.c_str(), 1);  // where the grader makes its scratch folder
        setenv("FAKE_RENDERER_PID_FILE", pid_file.c_str(), 1);
        const int null = open("/dev/null", O_WRONLY);
        dup2(null, 1);
        execl(RAYTRACER_GRADE, RAYTRACER_GRADE, "--raytracer", FAKE_HANG, "--only", "testAmbient",
              COURSE_SCENES, static_cast<char*>(nullptr));
        _exit(127);
    }
    CHECK(wait_for_file(pid_file));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the pid is written before the hang
    pid_t render = 0;
    std::ifstream(pid_file) >> render;
    CHECK(render > 0 && kill(render, 0) == 0);  // the render runs
    CHECK(!fs::is_empty(temporary));            // and the scratch folder exists

    kill(grader, signal);
    int status = 0;
    CHECK(wait_for_exit(grader, status));
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == signal);
    CHECK(render > 0 && kill(render, 0) == -1 && errno == ESRCH);  // killed and reaped
    CHECK(fs::is_empty(temporary));
    if (render > 0) kill(render, SIGKILL);
}

// Whether the process has ended but is not yet reaped (Linux's /proc; elsewhere false).
bool is_zombie(pid_t pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    std::getline(stat, line);
    const std::size_t name_end = line.rfind(')');  // "pid (name) state ..."
    return name_end != std::string::npos && name_end + 2 < line.size() && line[name_end + 2] == 'Z';
}

// How grade_shadow() runs the grader besides: its standard input, and whether as the
// user nobody where this test runs as root (root removes anything, write-protected or not).
struct GraderRun {
    int stdin_fd = -1;  // -1: this process's
    bool as_nobody = false;
};
constexpr uid_t kNobody = 65534;
constexpr int kCannotDropPrivileges = 126;  // the grader's child exit status where it could not

// Runs the grader on testShadow with the renderer, its standard output `stdout_fd` and
// TMPDIR `temporary`; returns its wait status.
int grade_shadow(const char* renderer, int stdout_fd, const fs::path& temporary, GraderRun run = {}) {
    const pid_t grader = fork();
    if (grader == 0) {
        setenv("TMPDIR", temporary.c_str(), 1);
        dup2(stdout_fd, 1);
        if (run.stdin_fd >= 0) dup2(run.stdin_fd, 0);
        if (run.as_nobody && geteuid() == 0 &&
            (setgid(kNobody) != 0 || setuid(kNobody) != 0 || access(RAYTRACER_GRADE, X_OK) != 0 ||
             access(renderer, X_OK) != 0 || access(COURSE_SCENES "/testShadow.txt", R_OK) != 0))
            _exit(kCannotDropPrivileges);
        execl(RAYTRACER_GRADE, RAYTRACER_GRADE, "--raytracer", renderer, "--only", "testShadow",
              COURSE_SCENES, static_cast<char*>(nullptr));
        _exit(127);
    }
    int status = 0;
    CHECK(wait_for_exit(grader, status));
    return status;
}

}  // namespace

TEST(sigterm_kills_the_render_and_removes_the_scratch_folder) { interrupt_a_hanging_render(SIGTERM); }
TEST(sigint_kills_the_render_and_removes_the_scratch_folder) { interrupt_a_hanging_render(SIGINT); }

// `raytracer-grade | head -c 10`: the reader is gone before the report is out.
TEST(a_closed_report_pipe_ends_the_grading_and_removes_the_scratch_folder) {
    const Root root;
    int report[2];
    CHECK_EQ(pipe(report), 0);
    close(report[0]);
    const int status = grade_shadow(FAKE_ONE_LEVEL, report[1], root.path / "tmp");
    close(report[1]);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGPIPE);
    CHECK(fs::is_empty(root.path / "tmp"));
}

TEST(a_report_that_cannot_be_written_is_status_3) {
    const Root root;
    const int full = open("/dev/full", O_WRONLY);
    CHECK(full >= 0);
    const int status = grade_shadow(FAKE_ONE_LEVEL, full, root.path / "tmp");
    close(full);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 3);
    CHECK(fs::is_empty(root.path / "tmp"));
}

TEST(a_temporary_folder_that_is_missing_is_status_3) {
    const Root root;
    const int null = open("/dev/null", O_WRONLY);
    const int status = grade_shadow(FAKE_ONE_LEVEL, null, root.path / "missing");
    close(null);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 3);
    CHECK(!fs::exists(root.path / "missing"));
}

// A renderer that exits but leaves a process of its group running: it is killed.
TEST(what_a_render_leaves_running_is_stopped) {
    const Root root;
    const fs::path pid_file = root.path / "straggler.pid";
    setenv("FAKE_RENDERER_PID_FILE", pid_file.c_str(), 1);
    const int null = open("/dev/null", O_WRONLY);
    const int status = grade_shadow(FAKE_STRAGGLER, null, root.path / "tmp");
    close(null);
    unsetenv("FAKE_RENDERER_PID_FILE");
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);  // the key itself: it passes
    CHECK(wait_for_file(pid_file));
    pid_t straggler = 0;
    std::ifstream(pid_file) >> straggler;
    CHECK(straggler > 0);
    bool gone = false;  // killed, then reaped by init (or a zombie where init does not reap)
    for (int i = 0; i < 500 && !gone && straggler > 0; ++i) {
        gone = (kill(straggler, 0) == -1 && errno == ESRCH) || is_zombie(straggler);
        if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    CHECK(gone);
    if (!gone && straggler > 0) kill(straggler, SIGKILL);
}

// A renderer that waits for Enter at its end (as student programs do) gets end of file
// at once: its standard input is not the grader's, which here stays open and silent.
TEST(a_render_that_reads_standard_input_gets_its_end) {
    const Root root;
    int input[2];
    CHECK_EQ(pipe(input), 0);
    const int null = open("/dev/null", O_WRONLY);
    GraderRun run;
    run.stdin_fd = input[0];
    const int status = grade_shadow(FAKE_WAITS_FOR_ENTER, null, root.path / "tmp", run);
    close(null);
    close(input[0]);
    close(input[1]);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);  // the key itself, not a timeout
    CHECK(fs::is_empty(root.path / "tmp"));
}

// What a render made write-protected (a folder with mode 500 and a file in it) is
// removed with the scratch folder, by a grader that is not root.
TEST(a_write_protected_folder_a_render_leaves_is_removed) {
    const Root root;
    fs::permissions(root.path, fs::perms::all);  // nobody makes its scratch folder there
    fs::permissions(root.path / "tmp", fs::perms::all);
    const int null = open("/dev/null", O_WRONLY);
    GraderRun run;
    run.as_nobody = true;
    const int status = grade_shadow(FAKE_READONLY_FOLDER, null, root.path / "tmp", run);
    close(null);
    if (WIFEXITED(status) && WEXITSTATUS(status) == kCannotDropPrivileges) {
        std::fprintf(stderr,
                     "note: the grader could not run as nobody here (the build's folders); not tried\n");
        return;
    }
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    CHECK(fs::is_empty(root.path / "tmp"));
}
