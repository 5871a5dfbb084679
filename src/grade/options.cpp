#include "options.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "raytracer/scene_numbers.h"

namespace grade {

namespace {

// The options that take a value, as --name VALUE or --name=VALUE.
std::filesystem::path* path_option(const std::string& name, Options& options) {
    if (name == "--raytracer") return &options.raytracer;
    if (name == "--keys") return &options.keys;
    if (name == "--diff-dir") return &options.diff_dir;
    if (name == "--html") return &options.html;
    return nullptr;
}

std::string set_timeout(const std::string& value, Options& options) {
    // A decimal number as a scene's are read (no hex, spaces, "inf" or "nan").
    const std::optional<double> seconds = rt::to_double(value);
    if (!seconds || *seconds <= 0 || *seconds > 1e6)
        return "--timeout '" + value + "' is not a number of seconds above 0 and at most 1000000";
    options.timeout_seconds = *seconds;
    return {};
}

}  // namespace

std::string parse_command_line(int argc, char** argv, Options& options) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    std::vector<std::string> given;  // each option at most once, as a repeat is a slip
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string name = args[i], value;
        const std::size_t equals = name.rfind("--", 0) == 0 ? name.find('=') : std::string::npos;
        if (equals != std::string::npos) value = name.substr(equals + 1), name.resize(equals);
        if (name == "--help" || name == "-h") {
            if (equals != std::string::npos) return name + " takes no value";
            options.help = true;
            continue;
        }
        if (name.empty() || name[0] != '-') {
            if (!options.scenes.empty())
                return "two scene folders, '" + options.scenes.u8string() + "' and '" + name +
                       "', expected one";
            if (name.empty()) return "an empty scene folder name";
            options.scenes = std::filesystem::u8path(name);
            continue;
        }
        if (path_option(name, options) == nullptr && name != "--only" && name != "--timeout")
            return "unknown option '" + args[i] + "'";
        if (equals == std::string::npos) {
            if (i + 1 >= args.size()) return name + " needs a value";
            value = args[++i];
        }
        if (value.empty()) return name + " needs a value, not an empty one";
        if (std::find(given.begin(), given.end(), name) != given.end()) return name + " given twice";
        given.push_back(name);
        if (std::filesystem::path* path = path_option(name, options)) {
            *path = std::filesystem::u8path(value);
        } else if (name == "--only") {  // testShadow or testShadow.txt
            const bool has_txt = value.size() > 4 && value.compare(value.size() - 4, 4, ".txt") == 0;
            options.only = has_txt ? value.substr(0, value.size() - 4) : value;
        } else if (std::string error = set_timeout(value, options); !error.empty()) {
            return error;
        }
    }
    return {};
}

std::string help_text(const std::string& default_scenes) {
    return "usage: raytracer-grade [--raytracer EXE] [--keys DIR] [--only NAME]\n"
           "                       [--timeout SECONDS] [--diff-dir DIR] [--html FILE]\n"
           "                       [SCENES_DIR]\n"
           "\n"
           "Renders every *.txt scene of SCENES_DIR with raytracer.exe, one process per\n"
           "scene in an empty scratch folder, as the course's grading script does, and\n"
           "compares each image with its key (testX.txt -> keyX.ppm).\n"
           "\n"
           "  SCENES_DIR         default: " +
           default_scenes +
           "\n"
           "  --raytracer EXE    the program to grade (default: raytracer.exe beside this\n"
           "                     program)\n"
           "  --keys DIR         the key images (default: keys/ beside SCENES_DIR)\n"
           "  --only NAME        grade only the scene NAME.txt (e.g. testShadow)\n"
           "  --timeout SECONDS  kill a render that takes longer (default 60)\n"
           "  --diff-dir DIR     write DIR/<scene>.png for each failing scene: key, yours\n"
           "                     and their difference side by side\n"
           "  --html FILE        write one page with the marks and the difference pictures\n"
           "\n"
           "The pass rule (SPEC section 7), per scene: the image must be a binary PPM (P6)\n"
           "of the key's size, and each pixel that differs from the key must be\n"
           "explainable: either every channel is off by at most one level (a truncation\n"
           "step of the arithmetic; at most 12 such pixels, SPEC's dozen: more are a\n"
           "systematic difference, such as rounding instead of truncating), or the pixel\n"
           "is one of the key's known ambiguous pixels (an eye ray exactly tangent to an\n"
           "ellipsoid, or through the rim where the near plane cuts one) and shows the\n"
           "other outcome there, within a truncation step. Any other differing pixel\n"
           "fails the scene: the course gives no partial marks. A passing scene earns 2\n"
           "marks.\n"
           "\n"
           "Options take their value as --name VALUE or --name=VALUE, each at most once.\n"
           "\n"
           "Exit status: 0 when every scene passes, 1 when one fails, 2 on a bad command\n"
           "line (or --only naming no scene), 3 when the grader cannot read the scene\n"
           "folder or write its scratch folder, pictures, page or report, 77 when the\n"
           "scene folder does not exist.\n";
}

}  // namespace grade
