// The grader: renders every *.txt scene of a folder with raytracer.exe, as the course's
// grading script does (one process per scene, in a scratch folder), and compares each
// image with its key pixel by pixel. Prints a row per scene and a total.
//
//   grade [--raytracer EXE] [--keys DIR] [--only NAME] [--max-pixels N] [--max-total N] [SCENES_DIR]
//
// A scene passes when its image has the key's size and differs from it in at most
// --max-pixels pixels (default 12, SPEC section 7); the run passes when every scene
// passes and all differ in at most --max-total pixels (default 12). Exit status 0 on
// a pass, 1 on a fail, 2 on a bad command line, 77 when the scene folder is absent
// (CTest reports that as skipped).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "raytracer/image.h"
#include "raytracer/parser.h"
#include "raytracer/ppm.h"
#include "raytracer/scene_error.h"

namespace fs = std::filesystem;

#ifndef RAYTRACER_DEFAULT_SCENES
#define RAYTRACER_DEFAULT_SCENES "../shared/course-tests/scenes"
#endif

namespace {

constexpr int kSkipped = 77;

struct Options {
    fs::path raytracer;
    fs::path scenes = RAYTRACER_DEFAULT_SCENES;
    fs::path keys;
    std::string only;
    long long max_pixels = 12;
    long long max_total = 12;
};

// The key of testName.txt is keyName.ppm (the course's naming); of other.txt, other.ppm.
fs::path key_for(const fs::path& keys, const fs::path& scene) {
    const std::string stem = scene.stem().string();
    if (stem.rfind("test", 0) == 0) return keys / ("key" + stem.substr(4) + ".ppm");
    return keys / (stem + ".ppm");
}

// Runs raytracer.exe on the scene with the scratch folder as the working directory,
// as a grading script would. Returns the exit status std::system reports.
int run_raytracer(const fs::path& raytracer, const fs::path& scene, const fs::path& folder) {
    const fs::path previous = fs::current_path();
    fs::current_path(folder);
    std::string command = "\"" + raytracer.string() + "\" \"" + scene.string() + "\"";
#ifdef _WIN32
    command = "\"" + command + "\"";  // cmd.exe strips one outer pair of quotes
#endif
    const int status = std::system(command.c_str());
    fs::current_path(previous);
    return status;
}

bool parse_arguments(int argc, char** argv, Options& options) {
    std::vector<std::string> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const bool has_value = i + 1 < args.size();
        try {
            if (a == "--raytracer" && has_value)
                options.raytracer = args[++i];
            else if (a == "--keys" && has_value)
                options.keys = args[++i];
            else if (a == "--only" && has_value)
                options.only = args[++i];
            else if (a == "--max-pixels" && has_value)
                options.max_pixels = std::stoll(args[++i]);
            else if (a == "--max-total" && has_value)
                options.max_total = std::stoll(args[++i]);
            else if (!a.empty() && a[0] != '-')
                options.scenes = a;
            else
                return false;
        } catch (const std::exception&) {
            return false;
        }
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    if (!parse_arguments(argc, argv, options)) {
        std::cerr << "usage: grade [--raytracer EXE] [--keys DIR] [--only NAME] [--max-pixels N] "
                     "[--max-total N] [SCENES_DIR]\n";
        return 2;
    }
    if (options.raytracer.empty())
        options.raytracer = fs::absolute(argv[0]).parent_path().parent_path() / "raytracer.exe";
    if (options.keys.empty()) options.keys = options.scenes.parent_path() / "keys";

    std::error_code ec;
    if (!fs::is_directory(options.scenes, ec)) {
        std::cout << "SKIPPED: no scene folder at " << options.scenes.string()
                  << " (set RAYTRACER_COURSE_TESTS or pass SCENES_DIR)\n";
        return kSkipped;
    }
    if (!fs::exists(options.raytracer, ec)) {
        std::cerr << "grade: error: no raytracer at " << options.raytracer.string() << " (use --raytracer)\n";
        return 2;
    }
    options.raytracer = fs::absolute(options.raytracer);

    std::vector<fs::path> scenes;
    for (const fs::directory_entry& entry : fs::directory_iterator(options.scenes)) {
        const fs::path& p = entry.path();
        if (p.extension() == ".txt" && (options.only.empty() || p.stem() == options.only))
            scenes.push_back(p);
    }
    std::sort(scenes.begin(), scenes.end());
    if (scenes.empty()) {
        std::cerr << "grade: error: no scene " << (options.only.empty() ? "*.txt" : options.only) << " in "
                  << options.scenes.string() << "\n";
        return 1;
    }

    std::mt19937_64 random(std::random_device{}());
    const fs::path scratch = fs::temp_directory_path() / ("raytracer-grade-" + std::to_string(random()));
    fs::create_directories(scratch);

    std::printf("%-22s %10s %8s %9s  %-6s %s\n", "scene", "differing", "largest", "time ms", "result",
                "marks");
    long long total_differing = 0;
    int marks = 0;
    bool all_passed = true;
    for (const fs::path& scene_path : scenes) {
        const fs::path scene = fs::absolute(scene_path);
        const std::string name = scene.stem().string();
        std::string problem;
        rt::ImageDiff diff;
        double milliseconds = 0;
        try {
            const rt::Scene parsed = rt::load_scene(scene.string());
            const fs::path output = scratch / fs::u8path(parsed.output);
            fs::remove(output, ec);
            const auto start = std::chrono::steady_clock::now();
            const int status = run_raytracer(options.raytracer, scene, scratch);
            milliseconds =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            rt::Image rendered, key;
            std::string error;
            if (status != 0)
                problem = "raytracer.exe failed (status " + std::to_string(status) + ")";
            else if (!rt::read_ppm(output.string(), rendered, error) ||
                     !rt::read_ppm(key_for(options.keys, scene).string(), key, error))
                problem = error;
            else
                diff = rt::compare_images(rendered, key);
            if (problem.empty() && !diff.same_size) problem = "image size differs from the key";
            fs::remove(output, ec);
        } catch (const std::exception& e) {
            problem = e.what();
        }
        const bool passed = problem.empty() && diff.differing_pixels <= options.max_pixels;
        all_passed = all_passed && passed;
        if (passed) marks += 2;
        if (problem.empty()) {
            total_differing += diff.differing_pixels;
            std::printf("%-22s %10lld %8d %9.1f  %-6s %d/2\n", name.c_str(), diff.differing_pixels,
                        diff.largest_difference, milliseconds, passed ? "pass" : "FAIL", passed ? 2 : 0);
        } else {
            std::printf("%-22s %10s %8s %9.1f  %-6s 0/2  %s\n", name.c_str(), "-", "-", milliseconds, "FAIL",
                        problem.c_str());
        }
        std::fflush(stdout);
    }
    fs::remove_all(scratch, ec);

    const bool ok = all_passed && total_differing <= options.max_total;
    std::printf("total: %lld differing pixels in %zu scenes (at most %lld allowed), marks %d/%zu: %s\n",
                total_differing, scenes.size(), options.max_total, marks, 2 * scenes.size(),
                ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
