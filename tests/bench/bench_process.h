// What the benchmark's tables share: running a whole process and timing it, the
// statistics of a series of runs, and the rows they print.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#ifdef _WIN32
#include <process.h>
#else
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX asks programs to declare it
#endif

namespace bench {

using Clock = std::chrono::steady_clock;

// One finished run: wall time in seconds (-1 on failure) and peak resident memory in
// bytes (0 where the system does not report it).
struct Run {
    double seconds = -1;
    double peak_bytes = 0;
};

// Runs a program with its output thrown away and waits for it.
inline Run run_measured(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    args.reserve(argv.size() + 1);
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const auto start = Clock::now();
    Run result;
#ifdef _WIN32
    const intptr_t status = _spawnv(_P_WAIT, args[0], args.data());
    const bool ok = status == 0;
#else
    pid_t pid = 0;
    posix_spawn_file_actions_t quiet;
    posix_spawn_file_actions_init(&quiet);
    posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
    bool ok = posix_spawn(&pid, args[0], &quiet, nullptr, args.data(), environ) == 0;
    posix_spawn_file_actions_destroy(&quiet);
    int status = 0;
    rusage usage{};
    ok = ok && wait4(pid, &status, 0, &usage) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    result.peak_bytes = double(usage.ru_maxrss) * 1024;  // kilobytes on Linux
#endif
    const std::chrono::duration<double> took = Clock::now() - start;
    result.seconds = ok ? took.count() : -1;
    return result;
}

inline double run(const std::vector<std::string>& argv) { return run_measured(argv).seconds; }

struct Stats {
    std::vector<double> samples;
    double min() const { return *std::min_element(samples.begin(), samples.end()); }
    double max() const { return *std::max_element(samples.begin(), samples.end()); }
    double median() const {
        std::vector<double> s = samples;
        std::sort(s.begin(), s.end());
        const std::size_t n = s.size();
        return n % 2 ? s[n / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
    }
};

// A row of min, median and max, in milliseconds (or in seconds times unit).
inline void print_row(const std::string& name, const Stats& s, const std::string& tail, double unit = 1e3) {
    std::printf("  %-18s %8.2f %8.2f %8.2f  %s\n", name.c_str(), s.min() * unit, s.median() * unit,
                s.max() * unit, tail.c_str());
}

inline std::string format(const char* f, double x) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, f, x);
    return buffer;
}

}  // namespace bench
