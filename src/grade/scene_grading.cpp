#include "scene_grading.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <new>
#include <system_error>
#include <thread>

#include "child_process.h"
#include "raytracer/parser.h"
#include "raytracer/ppm.h"
#include "raytracer/shown.h"

namespace fs = std::filesystem;

namespace grade {
namespace {

// The first non-empty line among the first kStderrRead bytes of a run's stderr: a program
// that writes gigabytes without a newline costs the grader no more than that.
constexpr std::size_t kStderrRead = std::size_t{64} << 10;
std::string first_line_of(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string text(kStderrRead, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    for (std::size_t start = 0; start < text.size();) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (!line.empty()) return rt::escaped(line, 200);  // no escape sequence reaches the terminal
        start = end + 1;
    }
    return {};
}

std::string format_seconds(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g s", seconds);
    return text;
}

// What a run that did not exit with status 0 did, in the student's words.
std::string describe_failed_run(const ChildOutcome& run, const Options& options,
                                const fs::path& stderr_file) {
    using End = ChildOutcome::End;
    const std::string said = first_line_of(stderr_file);
    switch (run.end) {
        case End::not_started:
            return "could not start " + options.raytracer.string() + ": " + run.why_not_started;
        case End::timed_out:
            return "still running after " + format_seconds(options.timeout_seconds) + " (--timeout): killed";
        case End::interrupted:
            return "interrupted: the grader was stopped";
        case End::killed_by_signal:
            return "killed by " + signal_name(run.code) + (said.empty() ? "" : ": " + said);
        case End::exited:
            break;
    }
    const std::string crash = windows_crash_name(static_cast<unsigned long>(static_cast<unsigned>(run.code)));
    if (!crash.empty()) return "crashed with " + crash + (said.empty() ? "" : ": " + said);
    return "exited with status " + std::to_string(run.code) +
           (said.empty() ? " and said nothing on stderr" : ": " + said);
}

// What a file type other than a regular file or a folder is, for a message; empty where
// nothing is there.
std::string not_a_file(fs::file_type type) {
    switch (type) {
        case fs::file_type::symlink:
            return "a symbolic link";
        case fs::file_type::fifo:
            return "a FIFO";
        case fs::file_type::socket:
            return "a socket";
        case fs::file_type::block:
        case fs::file_type::character:
            return "a device";
        case fs::file_type::not_found:
        case fs::file_type::none:
            return {};
        default:
            return "something other than a file";
    }
}

// The files a run left in its folder, for the student who named the output wrongly.
std::string files_in(const fs::path& folder) {
    std::vector<std::string> names;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(folder, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
        if (it->is_regular_file(ec)) names.push_back(fs::relative(it->path(), folder, ec).generic_string());
    std::sort(names.begin(), names.end());
    if (names.empty()) return "it wrote no file at all";
    std::string list = "it wrote: ";
    for (std::size_t i = 0; i < names.size() && i < 10; ++i) list += (i ? ", " : "") + names[i];
    if (names.size() > 10) list += ", and " + std::to_string(names.size() - 10) + " more";
    return list;
}

// Reads the image the run wrote; returns why not, for the student. Its size is checked
// against the key's before its pixels are read, so that a header cannot make the grader
// take gigabytes.
std::string read_output(const fs::path& folder, const std::string& output_name, const rt::Image& key,
                        rt::Image& image, std::vector<std::string>& notes) {
    // Only a name in the run's folder: an absolute path or one with '..' would grade a
    // file that was there before the run (raytracer.exe refuses such an OUTPUT itself).
    const fs::path name = fs::u8path(output_name);
    if (name.has_root_name() || name.has_root_directory() ||
        std::any_of(name.begin(), name.end(), [](const fs::path& part) { return part == ".."; }))
        return "OUTPUT " + rt::shown(output_name, rt::kMaxShownPath) +
               " is outside the run's folder, expected a file name in it";
    const fs::path output = folder / name;
    std::error_code ec;
    // The file itself, not what a link there names: a link to the key is no image written.
    const fs::file_status status = fs::symlink_status(output, ec);
    if (fs::is_directory(status)) return "wrote a folder named " + output_name + " (OUTPUT of the scene)";
    if (!fs::is_regular_file(status)) {
        const std::string what = not_a_file(status.type());
        if (!what.empty())
            return "wrote " + what + " named " + output_name + " (OUTPUT of the scene), not a file";
        return "wrote nothing named " + output_name + " (OUTPUT of the scene); " + files_in(folder);
    }
    char magic[2] = {0, 0};
    std::ifstream(output, std::ios::binary).read(magic, 2);
    if (magic[0] == 'P' && magic[1] == '3') return "P3 written; the course requires P6";
    std::string error;
    int width = 0, height = 0;
    if (rt::read_ppm_size(output.u8string(), width, height, error) &&
        (width != key.width || height != key.height))
        return "wrote " + std::to_string(width) + "x" + std::to_string(height) + ", the key is " +
               std::to_string(key.width) + "x" + std::to_string(key.height);
    std::uint64_t bytes_after = 0;
    if (error.empty() && rt::read_ppm(output.u8string(), image, error, &bytes_after)) {
        // Read twice (its size, then the file): a program that left something running
        // may have replaced it in between.
        if (image.width != key.width || image.height != key.height)
            return "wrote " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                   ", the key is " + std::to_string(key.width) + "x" + std::to_string(key.height);
        if (bytes_after > 0)
            notes.push_back(rt::plural(static_cast<long long>(bytes_after), "byte", "bytes") +
                            " after the pixels, where a P6 file ends");
        return {};
    }
    // The file as the scene names it, not the scratch folder's path to it.
    const std::string scratch_path = rt::shown(output.u8string(), rt::kMaxShownPath);
    const std::size_t at = error.find(scratch_path);
    if (at != std::string::npos)
        error.replace(at, scratch_path.size(), rt::shown(output_name, rt::kMaxShownPath));
    return error;
}

// The handout asks for 5 s at 400x400 in Release; larger images get proportionally longer.
void note_if_slow(SceneResult& result) {
    const double pixels = static_cast<double>(result.key.width) * result.key.height;
    const double allowed = 5.0 * std::max(1.0, pixels / (400.0 * 400.0));
    if (result.seconds > allowed)
        result.notes.push_back("took " + format_seconds(result.seconds) +
                               ", over the handout's 5 s for 400x400 (" + format_seconds(allowed) + " at " +
                               std::to_string(result.key.width) + "x" + std::to_string(result.key.height) +
                               ")");
}

// Gives the owner every permission on each folder under folder and write permission on
// each file (not through symbolic links), so that what a run made write-protected
// ("chmod 500 sub", a copy of a read-only folder; on Windows a read-only file) can be
// removed.
void make_removable(const fs::path& folder) {
    std::error_code ec, ignored;
    fs::permissions(folder, fs::perms::owner_all, fs::perm_options::add, ignored);
    // Each folder is met before it is entered, so its permissions come first.
    for (auto it = fs::recursive_directory_iterator(folder, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
        if (const fs::file_type type = it->symlink_status(ignored).type(); type == fs::file_type::directory)
            fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ignored);
        else if (type == fs::file_type::regular)
            fs::permissions(it->path(), fs::perms::owner_write, fs::perm_options::add, ignored);
}
}  // namespace

bool remove_folder(const fs::path& folder) {
    // On Windows a file can stay locked for a moment after its program ended (a virus
    // scanner, Wine's debugger after a crash): a few tries, then it is left for the end.
    std::error_code ec;
    for (int attempt = 0; attempt < 25; ++attempt) {
        fs::remove_all(folder, ec);
        if (!ec) return true;
        if (attempt == 0) make_removable(folder);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

fs::path key_for(const fs::path& keys, const fs::path& scene) {
    const std::string stem = scene.stem().string();
    if (stem.rfind("test", 0) == 0) return keys / ("key" + stem.substr(4) + ".ppm");
    return keys / (stem + ".ppm");
}

SceneResult grade_scene(const fs::path& scene, const Options& options, const fs::path& scratch) {
    SceneResult result;
    result.name = scene.stem().string();
    const fs::path key_file = key_for(options.keys, scene);
    result.key_name = key_file.stem().string();
    std::string output_name, error;
    try {
        output_name = rt::load_scene(scene.string()).output;
    } catch (const std::exception& e) {
        result.problem = std::string("the scene itself cannot be read: ") + e.what();
        result.ungradable = true;
        return result;
    }
    bool key_read = false;
    try {
        key_read = rt::read_ppm(key_file.u8string(), result.key, error);
    } catch (const std::bad_alloc&) {  // a real image too large for this machine
        error = "out of memory reading " + rt::shown(key_file.u8string(), rt::kMaxShownPath);
    }
    if (!key_read) {
        result.problem = "no usable key: " + error;
        result.ungradable = true;
        return result;
    }
    // A folder of the scene's own: one that a crashed program's files keep from removal
    // cannot leave files in the next scene's folder.
    const fs::path folder = scratch / ("run-" + result.name);
    remove_folder(folder);
    // The scratch folder is the grader's: a program run before may have taken its
    // permissions (chmod 555 ..), which would keep every later scene from its run.
    std::error_code made;
    fs::permissions(scratch, fs::perms::owner_all, fs::perm_options::add, made);
    fs::create_directories(folder, made);
    if (made) {
        result.problem = "the grader cannot make the run's folder " +
                         rt::shown(folder.u8string(), rt::kMaxShownPath) + ": " + made.message();
        result.ungradable = result.scratch_unwritable = true;
        return result;
    }
    // Of stderr only the start is read (its standard output not at all).
    const ChildCommand command{options.raytracer,      {scene.string()},        folder,
                               scratch / "stderr.txt", options.timeout_seconds, kStderrRead};
    const ChildOutcome run = run_child(command);
    result.seconds = run.seconds;
    result.interrupted = run.end == ChildOutcome::End::interrupted || interrupting_signal() != 0;
    if (run.end != ChildOutcome::End::exited || run.code != 0)
        result.problem = describe_failed_run(run, options, command.stderr_file);
    else
        result.problem = read_output(folder, output_name, result.key, result.got, result.notes);
    if (result.problem.empty()) result.judgement = judge(result.key_name, result.key, result.got);
    if (run.end == ChildOutcome::End::exited) note_if_slow(result);
    remove_folder(folder);
    return result;
}

}  // namespace grade
