#include "options.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace grade {

std::string parse_command_line(int argc, char** argv, Options& options) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--help" || a == "-h") {
            options.help = true;
            continue;
        }
        const bool takes_value = a == "--raytracer" || a == "--keys" || a == "--only" || a == "--timeout" ||
                                 a == "--diff-dir" || a == "--html";
        if (takes_value && i + 1 >= args.size()) return a + " needs a value";
        if (a == "--raytracer") {
            options.raytracer = std::filesystem::u8path(args[++i]);
        } else if (a == "--keys") {
            options.keys = std::filesystem::u8path(args[++i]);
        } else if (a == "--only") {
            options.only = args[++i];
        } else if (a == "--diff-dir") {
            options.diff_dir = std::filesystem::u8path(args[++i]);
        } else if (a == "--html") {
            options.html = std::filesystem::u8path(args[++i]);
        } else if (a == "--timeout") {
            const std::string& value = args[++i];
            std::size_t used = 0;
            double seconds = 0;
            try {
                seconds = std::stod(value, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != value.size() || !std::isfinite(seconds) || seconds <= 0 || seconds > 1e6)
                return "--timeout '" + value + "' is not a number of seconds between 0 and 1000000";
            options.timeout_seconds = seconds;
        } else if (!a.empty() && a[0] != '-') {
            options.scenes = std::filesystem::u8path(a);
        } else {
            return "unknown option '" + a + "'";
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
           "step of the arithmetic), or the pixel is one of the key's known\n"
           "ambiguous pixels (an eye ray exactly tangent to an ellipsoid, or through the\n"
           "rim where the near plane cuts one). Any other differing pixel fails the scene:\n"
           "the course gives no partial marks. A passing scene earns 2 marks.\n"
           "\n"
           "Exit status: 0 when every scene passes, 1 when one fails, 2 on a bad command\n"
           "line, 77 when the scene folder does not exist.\n";
}

}  // namespace grade
