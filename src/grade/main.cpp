// raytracer-grade: grades a ray tracer against the course keys as the course's grading
// script does, strictly (SPEC section 7), and shows where an image differs. --help says how.
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include "child_process.h"
#include "diff_picture.h"
#include "html_page.h"
#include "options.h"
#include "png.h"
#include "report.h"
#include "scene_grading.h"

#ifdef _WIN32
#include <windows.h>
#endif

#ifndef RAYTRACER_DEFAULT_SCENES
#define RAYTRACER_DEFAULT_SCENES "../shared/course-tests/scenes"
#endif

namespace fs = std::filesystem;

namespace {

constexpr int kSkipped = 77;  // CTest's SKIP_RETURN_CODE of the golden tests

// The folder of this program, where raytracer.exe is by default (beside it, as installed
// and in the build folder). argv[0] is the fallback: it lacks the folder when found on PATH.
fs::path own_folder(const char* argv0) {
    std::error_code ec;
#ifdef _WIN32
    wchar_t buffer[32768];
    const DWORD size = GetModuleFileNameW(nullptr, buffer, 32768);
    if (size > 0 && size < 32768) return fs::path(std::wstring(buffer, size)).parent_path();
#else
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) return self.parent_path();
#endif
    return fs::absolute(argv0, ec).parent_path();
}

std::vector<fs::path> scenes_to_grade(const grade::Options& options) {
    std::vector<fs::path> scenes;
    for (const fs::directory_entry& entry : fs::directory_iterator(options.scenes)) {
        const fs::path& p = entry.path();
        if (p.extension() == ".txt" && (options.only.empty() || p.stem() == options.only))
            scenes.push_back(fs::absolute(p));
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

// Where the difference pictures go: --diff-dir, else a folder beside the HTML page.
fs::path picture_folder(const grade::Options& options) {
    if (!options.diff_dir.empty()) return options.diff_dir;
    if (options.html.empty()) return {};
    return options.html.parent_path() / (options.html.stem().string() + "-pictures");
}

// Writes the picture of a scene that failed on its pixels; returns its path, or empty.
fs::path write_picture(const grade::SceneResult& result, const fs::path& folder) {
    if (folder.empty() || !result.problem.empty() || result.passed()) return {};
    std::error_code ec;
    fs::create_directories(folder, ec);
    fs::path file = folder / (result.name + ".png");
    const std::string error =
        grade::write_png(file.string(), grade::difference_picture(result.key_name, result.key, result.got));
    if (error.empty()) return file;
    std::cerr << "raytracer-grade: " << error << "\n";
    return {};
}

// Fills the defaults; returns 0 to go on, else the exit status.
int complete_options(grade::Options& options, const char* argv0) {
    if (options.scenes.empty()) options.scenes = fs::u8path(RAYTRACER_DEFAULT_SCENES);
    if (options.raytracer.empty()) options.raytracer = own_folder(argv0) / "raytracer.exe";
    if (options.keys.empty()) options.keys = options.scenes.parent_path() / "keys";
    std::error_code ec;
    if (!fs::is_directory(options.scenes, ec)) {
        std::cout << "SKIPPED: no scene folder at " << options.scenes.string() << " (pass SCENES_DIR)\n";
        return kSkipped;
    }
    if (!fs::is_regular_file(options.raytracer, ec)) {
        std::cerr << "raytracer-grade: error: no program at " << options.raytracer.string()
                  << " (use --raytracer)\n";
        return 2;
    }
    options.raytracer = fs::absolute(options.raytracer);
    options.keys = fs::absolute(options.keys);
    return 0;
}

// Grades the scenes in order; stops early when the grader is interrupted.
std::vector<grade::SceneResult> grade_all(const std::vector<fs::path>& scenes, const grade::Options& options,
                                          const fs::path& scratch, std::vector<fs::path>& pictures) {
    std::vector<grade::SceneResult> results;
    grade::print_header();
    for (const fs::path& scene : scenes) {
        grade::SceneResult result = grade::grade_scene(scene, options, scratch);
        if (result.interrupted) break;
        pictures.push_back(write_picture(result, picture_folder(options)));
        grade::print_scene(result, pictures.back().generic_string());
        result.key = result.got = rt::Image{};  // the pictures are written; free the pixels
        results.push_back(std::move(result));
    }
    return results;
}

}  // namespace

int main(int argc, char** argv) {
    grade::Options options;
    const std::string error = grade::parse_command_line(argc, argv, options);
    if (options.help && error.empty()) {
        std::cout << grade::help_text(RAYTRACER_DEFAULT_SCENES);
        return 0;
    }
    if (!error.empty()) {
        std::cerr << "raytracer-grade: error: " << error << " (see --help)\n";
        return 2;
    }
    if (const int status = complete_options(options, argv[0]); status != 0) return status;
    const std::vector<fs::path> scenes = scenes_to_grade(options);
    if (scenes.empty()) {
        std::cerr << "raytracer-grade: error: no scene "
                  << (options.only.empty() ? "*.txt" : options.only + ".txt") << " in "
                  << options.scenes.string() << "\n";
        return 1;
    }

    grade::install_interrupt_handlers();
    std::mt19937_64 random(std::random_device{}());
    const fs::path scratch = fs::temp_directory_path() / ("raytracer-grade-" + std::to_string(random()));
    fs::create_directories(scratch);
    std::vector<fs::path> pictures;
    std::vector<grade::SceneResult> results;
    try {
        results = grade_all(scenes, options, scratch, pictures);
    } catch (const std::exception& e) {
        std::cerr << "raytracer-grade: error: " << e.what() << "\n";
    }
    grade::remove_folder(scratch);
    if (const int signal = grade::interrupting_signal(); signal != 0) {
        std::cerr << "raytracer-grade: interrupted; the render was stopped and the scratch folder removed\n";
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return 128 + signal;
    }
    if (results.size() != scenes.size()) return 1;
    const std::string summary = grade::print_summary(results);
    if (!options.html.empty()) {
        const std::string html_error = grade::write_html_page(options.html, results, pictures, summary);
        if (!html_error.empty())
            std::cerr << "raytracer-grade: " << html_error << "\n";
        else
            std::cout << "page: " << options.html.string() << "\n";
    }
    const bool all_passed =
        std::all_of(results.begin(), results.end(), [](const auto& r) { return r.passed(); });
    return all_passed ? 0 : 1;
}
