// raytracer-grade stopped by SIGTERM or SIGINT while a render hangs (POSIX): the grader
// ends by that signal, the render it started is killed and reaped, and the grader's scratch
// folder is gone from the temporary directory.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
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

void interrupt_a_hanging_render(int signal) {
    std::random_device random;
    const fs::path root =
        fs::temp_directory_path() / ("raytracer-grade-interrupt-" + std::to_string(random()));
    const fs::path temporary = root / "tmp", pid_file = root / "render.pid";
    fs::create_directories(temporary);

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
    fs::remove_all(root);
}

}  // namespace

TEST(sigterm_kills_the_render_and_removes_the_scratch_folder) { interrupt_a_hanging_render(SIGTERM); }
TEST(sigint_kills_the_render_and_removes_the_scratch_folder) { interrupt_a_hanging_render(SIGINT); }
