// Runs a program the way a grading script does (std::system, in a given working folder,
// stdout and stderr sent to files) and reports its exit status portably. Shared by the
// tests that drive raytracer.exe from outside.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#ifndef _WIN32
#include <sys/wait.h>  // WIFEXITED, WEXITSTATUS: std::system returns a wait status on POSIX
#endif

namespace run_program {

namespace fs = std::filesystem;

struct Result {
    int status = -1;  // the exit status; -1 when the program did not exit normally (a signal)
    std::string out;  // what it wrote to stdout
    std::string err;  // what it wrote to stderr
};

inline std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs program with args (none may contain a double quote) in folder, its standard input
// from the file `input` where one is named; the captured output goes through two files in
// capture_folder, which must not be folder itself.
inline Result run(const fs::path& program, const std::vector<std::string>& args, const fs::path& folder,
                  const fs::path& capture_folder, const fs::path& input = {}) {
    const fs::path out = capture_folder / "stdout.txt", err = capture_folder / "stderr.txt";
    std::string command = "\"" + program.string() + "\"";
    for (const std::string& arg : args) command += " \"" + arg + "\"";
    if (!input.empty()) command += " <\"" + input.string() + "\"";
    command += " >\"" + out.string() + "\" 2>\"" + err.string() + "\"";
#ifdef _WIN32
    command = "\"" + command + "\"";  // cmd.exe strips one outer pair of quotes
#endif
    const fs::path previous = fs::current_path();
    fs::current_path(folder);
    int raw = std::system(command.c_str());
#ifdef _WIN32
    // cmd.exe's 9009, "not recognized as a command", for a program that exists: under Wine a
    // start fails so now and then. Tried once more; a program that cannot start fails again.
    if (raw == 9009 && fs::exists(program)) raw = std::system(command.c_str());
#endif
    fs::current_path(previous);

    Result result;
#ifdef _WIN32
    result.status = raw;
#else
    result.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
#endif
    result.out = read_file(out);
    result.err = read_file(err);
    std::error_code ignored;
    fs::remove(out, ignored);
    fs::remove(err, ignored);
    return result;
}

}  // namespace run_program
