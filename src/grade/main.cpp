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
#include "raytracer/shown.h"
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

constexpr int kCannotReadOrWrite = 3;  // the scene folder, the scratch folder, pictures, page, report
constexpr int kSkipped = 77;           // CTest's SKIP_RETURN_CODE of the golden tests

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

// The *.txt files of the scene folder (--only: the one), sorted; empty with `error` set
// where the folder cannot be read.
std::vector<fs::path> scenes_to_grade(const grade::Options& options, std::error_code& error) {
    std::vector<fs::path> scenes;
    for (fs::directory_iterator it(options.scenes, error); !error && it != fs::directory_iterator();
         it.increment(error)) {
        const fs::path& p = it->path();
        std::error_code ignored;
        if (p.extension() == ".txt" && it->is_regular_file(ignored) &&
            (options.only.empty() || p.stem() == options.only))
            scenes.push_back(p);
    }
    if (error) scenes.clear();
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

// Where the difference pictures go: --diff-dir, else a folder beside the HTML page.
fs::path picture_folder(const grade::Options& options) {
    if (!options.diff_dir.empty()) return options.diff_dir;
    if (options.html.empty()) return {};
    return options.html.parent_path() / (options.html.stem().string() + "-pictures");
}

// Writes the picture of a scene that failed on its pixels; returns its path, or empty
// (with `failed` set where it could not be written).
fs::path write_picture(const grade::SceneResult& result, const fs::path& folder, bool& failed) {
    if (folder.empty() || !result.problem.empty() || result.passed()) return {};
    std::error_code ec;
    fs::create_directories(folder, ec);
    fs::path file = folder / (result.name + ".png");
    const rt::Image picture = grade::difference_picture(result.key_name, result.key, result.got);
    if (picture.rgb.empty()) return {};  // none for an image so wide
    const std::string error = ec ? "cannot make the folder '" + folder.string() + "': " + ec.message()
                                 : grade::write_png(file.u8string(), picture);
    if (error.empty()) return file;
    std::cerr << "raytracer-grade: error: " << error << "\n";
    failed = true;
    return {};
}

// Fills the defaults; returns 0 to go on, else the exit status. The scene folder is made
// absolute and lexically normal, so that "scenes/" and "." name their folder as
// "scenes" does, and the keys are found beside it.
int complete_options(grade::Options& options, const char* argv0) {
    if (options.scenes.empty()) options.scenes = fs::u8path(RAYTRACER_DEFAULT_SCENES);
    std::error_code ec;
    options.scenes = fs::absolute(options.scenes, ec).lexically_normal();
    if (!options.scenes.has_filename()) options.scenes = options.scenes.parent_path();
    if (options.raytracer.empty()) options.raytracer = own_folder(argv0) / "raytracer.exe";
    if (options.keys.empty()) options.keys = options.scenes.parent_path() / "keys";
    if (!fs::exists(options.scenes, ec)) {
        std::cout << "SKIPPED: no scene folder at " << options.scenes.string() << " (pass SCENES_DIR)\n";
        return kSkipped;
    }
    if (!fs::is_directory(options.scenes, ec)) {
        std::cerr << "raytracer-grade: error: " << options.scenes.string()
                  << " is not a folder, expected the folder of the scenes\n";
        return 2;
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

// Why the --html page may not be written where asked, found before any scene is graded:
// it would replace a scene or a key being graded, or any other of the scene or key folder
// (those --only leaves out: *.txt, *.ppm there), the program under test, a
// write-protected file, or something that is not a file. Empty to go on.
std::string html_refusal(const grade::Options& options, const std::vector<fs::path>& scenes) {
    std::error_code ec;
    const fs::file_status status = fs::status(options.html, ec);
    if (!fs::exists(status)) return {};
    const std::string page = "--html '" + options.html.string() + "'";
    if (!fs::is_regular_file(status)) return page + " is not a file";
    auto is = [&](const fs::path& other) { return fs::equivalent(options.html, other, ec); };
    for (const fs::path& scene : scenes) {
        if (is(scene)) return page + " is a scene being graded";
        if (is(grade::key_for(options.keys, scene))) return page + " is a key being graded";
    }
    // A scene or key --only leaves out (a page of an earlier run there may be replaced).
    const fs::path folder = fs::absolute(options.html, ec).parent_path(), type = options.html.extension();
    if (type == ".txt" && fs::equivalent(folder, options.scenes, ec))
        return page + " is a scene of the scene folder";
    if (type == ".ppm" && fs::equivalent(folder, options.keys, ec))
        return page + " is a key of the key folder";
    if (is(options.raytracer)) return page + " is the program being graded";
    if ((status.permissions() & fs::perms::owner_write) == fs::perms::none)
        return page + " is write-protected";
    return {};
}

// A new folder of the grader's own in the system's temporary folder; empty, with
// `error` set, where none can be made.
fs::path make_scratch_folder(std::string& error) {
    std::error_code ec;
    const fs::path temporary = fs::temp_directory_path(ec);
    if (ec) {
        error = "no temporary folder for the renders (" + ec.message() + "; set TMPDIR)";
        return {};
    }
    std::mt19937_64 random(std::random_device{}());
    fs::path scratch = temporary / ("raytracer-grade-" + std::to_string(random()));
    if (!fs::create_directories(scratch, ec)) {
        error = "cannot make a scratch folder in '" + temporary.string() +
                "': " + (ec ? ec.message() : std::string("it exists already"));
        return {};
    }
    return scratch;
}

// Grades the scenes in order; stops early when the grader is interrupted.
std::vector<grade::SceneResult> grade_all(const std::vector<fs::path>& scenes, const grade::Options& options,
                                          const fs::path& scratch, std::vector<fs::path>& pictures,
                                          bool& pictures_failed) {
    std::vector<grade::SceneResult> results;
    grade::print_header();
    for (const fs::path& scene : scenes) {
        grade::SceneResult result = grade::grade_scene(scene, options, scratch);
        if (result.interrupted) break;
        pictures.push_back(write_picture(result, picture_folder(options), pictures_failed));
        grade::print_scene(result, pictures.back().generic_string());
        // The pictures are written: the pixels are freed (moved from, not copied over, which
        // would keep their buffers: 1,500 scenes of 600x600 held 1.6 GB).
        result.key = rt::Image{};
        result.got = rt::Image{};
        results.push_back(std::move(result));
    }
    return results;
}

// Whether all that was printed on standard output reached it (not a full disk).
bool report_written() {
    std::cout.flush();
    return std::cout && std::fflush(stdout) == 0 && std::ferror(stdout) == 0;
}

int cannot_write_report() {
    std::cerr << "raytracer-grade: error: cannot write the report to standard output\n";
    return kCannotReadOrWrite;
}

// The scenes to grade, or the exit status that ends the run before any is graded.
int choose_scenes(const grade::Options& options, std::vector<fs::path>& scenes) {
    std::error_code unreadable;
    scenes = scenes_to_grade(options, unreadable);
    if (unreadable) {
        std::cerr << "raytracer-grade: error: cannot read the scene folder " << options.scenes.string()
                  << ": " << unreadable.message() << "\n";
        return kCannotReadOrWrite;
    }
    if (scenes.empty()) {
        std::cerr << "raytracer-grade: error: no scene "
                  << (options.only.empty() ? "*.txt" : options.only + ".txt") << " in "
                  << options.scenes.string() << "\n";
        return options.only.empty() ? 1 : 2;
    }
    if (options.html.empty()) return 0;
    const std::string refusal = html_refusal(options, scenes);
    if (refusal.empty()) return 0;
    std::cerr << "raytracer-grade: error: " << refusal << ", expected a new or replaceable page\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    grade::Options options;
    const std::string error = grade::parse_command_line(argc, argv, options);
    if (options.help && error.empty()) {
        std::cout << grade::help_text(RAYTRACER_DEFAULT_SCENES);
        return report_written() ? 0 : cannot_write_report();
    }
    if (!error.empty()) {
        std::cerr << "raytracer-grade: error: " << error << " (see --help)\n";
        return 2;
    }
    if (const int status = complete_options(options, argv[0]); status != 0) return status;
    std::vector<fs::path> scenes;
    if (const int status = choose_scenes(options, scenes); status != 0) return status;

    grade::install_interrupt_handlers();
    std::string scratch_error;
    const fs::path scratch = make_scratch_folder(scratch_error);
    if (scratch.empty()) {
        std::cerr << "raytracer-grade: error: " << scratch_error << "\n";
        return kCannotReadOrWrite;
    }
    std::vector<fs::path> pictures;
    std::vector<grade::SceneResult> results;
    bool pictures_failed = false;
    try {
        results = grade_all(scenes, options, scratch, pictures, pictures_failed);
    } catch (const std::exception& e) {
        std::cerr << "raytracer-grade: error: " << e.what() << "\n";
    }
    const bool removed = grade::remove_folder(scratch);
    if (!removed)
        std::cerr << "raytracer-grade: warning: the scratch folder "
                  << rt::shown(scratch.u8string(), rt::kMaxShownPath)
                  << " could not be removed in full; remove it by hand\n";
    if (const int signal = grade::interrupting_signal(); signal != 0) {
        std::cerr << "raytracer-grade: interrupted; the render was stopped"
                  << (removed ? " and the scratch folder removed\n" : "\n");
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return 128 + signal;
    }
    if (results.size() != scenes.size()) return 1;
    const std::string summary = grade::print_summary(results);
    bool page_written = true;
    if (!options.html.empty()) {
        const std::string html_error = grade::write_html_page(options.html, results, pictures, summary);
        page_written = html_error.empty();
        if (!page_written)
            std::cerr << "raytracer-grade: error: " << html_error << "\n";
        else
            std::cout << "page: " << options.html.string() << "\n";
    }
    if (!report_written()) return cannot_write_report();
    const bool scratch_unwritable =
        std::any_of(results.begin(), results.end(), [](const auto& r) { return r.scratch_unwritable; });
    if (!page_written || pictures_failed || scratch_unwritable) return kCannotReadOrWrite;
    const bool all_passed =
        std::all_of(results.begin(), results.end(), [](const auto& r) { return r.passed(); });
    return all_passed ? 0 : 1;
}
