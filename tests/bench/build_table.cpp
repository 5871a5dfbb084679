#include "build_table.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include "bench_process.h"

namespace fs = std::filesystem;

namespace {

// Lines of one file: its newlines, and one more for a last line without one.
std::size_t lines_of(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::size_t lines = 0;
    char last = '\n';
    for (std::istreambuf_iterator<char> c(in), end; c != end; ++c) lines += *c == '\n', last = *c;
    return lines + (last != '\n');
}

void size_rows(const fs::path& source) {
    std::size_t lines = 0, files = 0, longest = 0;
    fs::path longest_file;
    for (const char* top : {"src", "include"})
        for (const auto& entry : fs::recursive_directory_iterator(source / top)) {
            const fs::path& p = entry.path();
            const std::string ext = p.extension().string();
            if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
            if (p.lexically_relative(source).generic_string().rfind("src/grade/", 0) == 0) continue;
            const std::size_t n = lines_of(p);
            lines += n, ++files;
            if (n > longest) longest = n, longest_file = p.lexically_relative(source);
        }
    std::printf(
        "  src/ and include/ without the grader: %zu lines in %zu files (%s); the longest %s, %zu lines "
        "(%s)\n",
        lines, files, lines <= 3600 ? "met" : "not met", longest_file.generic_string().c_str(), longest,
        longest <= 400 ? "met" : "not met");
}

}  // namespace

void build_table(const BuildSetup& s, bool quick, bool& failed) {
    std::printf(
        "\n(f) size and build of raytracer.exe (target: <= 3,600 lines, no file over 400, "
        "built from scratch in <= 10 s)\n");
    size_rows(s.source);
    const fs::path dir = fs::absolute("build-from-scratch");
    std::vector<std::string> configure = {
        s.cmake.string(),   "-S" + s.source.string(),     "-B" + dir.string(),
        "-G" + s.generator, "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + s.compiler};
    if (!s.make_program.empty()) configure.push_back("-DCMAKE_MAKE_PROGRAM=" + s.make_program);
    const std::vector<std::string> build = {s.cmake.string(), "--build", dir.string(), "--target",
                                            "raytracer"};
    bench::Stats configured, built, total;
    for (int round = 0; round < (quick ? 1 : 3); ++round) {
        std::error_code ignored;
        fs::remove_all(dir, ignored);  // a fresh folder each round; the last goes with the scratch folder
        const double c = bench::run(configure);
        const double b = c < 0 ? -1 : bench::run(build);
        if (c < 0 || b < 0) {
            std::fprintf(stderr, "benchmark: configuring or building in %s failed\n", dir.string().c_str());
            failed = true;
            return;
        }
        configured.samples.push_back(c), built.samples.push_back(b), total.samples.push_back(c + b);
    }
    std::printf("  raytracer.exe from scratch (%s, Release), %zu round%s, seconds (min median max):\n",
                s.generator.c_str(), total.samples.size(), total.samples.size() == 1 ? "" : "s");
    bench::print_row("configure", configured, "", 1);
    bench::print_row("build", built, "", 1);
    bench::print_row("both", total, total.median() <= 10 ? "met" : "not met", 1);
}
