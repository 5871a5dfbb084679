// raytracer.exe <scene-file>: renders the scene and writes the P6 image its OUTPUT
// line names (or -o names). Exit statuses are listed in usage_text() and README.md.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#ifndef _WIN32
#include <fcntl.h>
#endif

#include "raytracer/command_line.h"
#include "raytracer/helper_pool.h"
#include "raytracer/interrupts.h"
#include "raytracer/output_policy.h"
#include "raytracer/parser.h"
#include "raytracer/ppm.h"
#include "raytracer/progress.h"
#include "raytracer/render.h"
#include "raytracer/scene_error.h"
#include "raytracer/scene_scale.h"
#include "raytracer/shown.h"
#include "raytracer/standard_streams.h"
#include "raytracer/version.h"

namespace {

enum ExitStatus : int {
    kSuccess = 0,
    kBadScene = 1,     // the scene file is missing, unreadable or wrong
    kBadUsage = 2,     // the command line is wrong
    kCannotWrite = 3,  // the image could not be written, or may not be written there
    kOutOfMemory = 4,
    kInternalError = 5,  // a failure the program did not foresee: a bug, please report it
    // 128 + the signal's number: interrupted (SIGINT, SIGTERM, SIGHUP; interrupts.h)
};

const char* usage_text() {
    return "usage: raytracer.exe [options] <scene-file>\n"
           "       raytracer.exe --help | -h | --version\n"
           "\n"
           "Renders a scene of ellipsoids and point lights (Phong shading, hard shadows,\n"
           "up to 3 mirror bounces) and writes it as a binary PPM (P6) to the file named\n"
           "by the scene's OUTPUT line. A scene file of - is read from standard input.\n"
           "\n"
           "Options (anywhere; a value as --threads N or --threads=N, --output=PATH too;\n"
           "--threads and -o at most once; -- ends the options):\n"
           "  -o PATH, --output PATH  write the image to PATH instead of OUTPUT; any path\n"
           "                          (not a write-protected file nor one in a folder it\n"
           "                          may not write), a device or a FIFO;\n"
           "                          -o - writes it to standard output\n"
           "  --threads N             read and render on N threads, 1 to 1024 (default: all\n"
           "                          cores); the image is the same, byte for byte, for\n"
           "                          any N\n"
           "  --progress, --quiet     show, or never show, the progress line (default: shown\n"
           "                          on a terminal once a render takes over a second)\n"
           "  --reference             render through the reference path: every ray against\n"
           "                          every ellipsoid, pixel by pixel (the same bytes,\n"
           "                          slower)\n"
           "\n"
           "Where the image goes: a scene's OUTPUT must be a file name relative to the\n"
           "working folder, in it or below it (no absolute path, no '..'), and a new or\n"
           "regular file other than the scene itself; anything else needs -o. The image\n"
           "appears only when complete and keeps the replaced file's permissions: an error\n"
           "or an interruption leaves nothing behind and an existing file as it was (a\n"
           "stream aside: -o -, a device, a FIFO, or on Linux -o /dev/fd/N for a\n"
           "descriptor the shell opened, written into as it is open).\n"
           "\n"
           "Scene file: one statement per line, fields separated by spaces or tabs,\n"
           "in any order:\n"
           "  NEAR n | LEFT l | RIGHT r | BOTTOM b | TOP t   (each exactly once)\n"
           "  RES columns rows                              (exactly once)\n"
           "  SPHERE name x y z sx sy sz r g b Ka Kd Ks Kr n  (any number)\n"
           "  LIGHT name x y z Ir Ig Ib                     (any number)\n"
           "  BACK r g b | AMBIENT Ir Ig Ib | OUTPUT file     (each exactly once)\n"
           "\n"
           "Exit status: 0 written; 1 bad scene file; 2 bad command line;\n"
           "3 image not writable or not allowed there; 4 out of memory; 5 internal error;\n"
           "128 + N interrupted by signal N (SIGINT 130, SIGHUP 129, SIGTERM 143).\n";
}

// Every message of the program: one line on stderr. A reader of stderr gone loses it,
// not the exit status (QuietBrokenPipe).
void say(const std::string& line) {
    const rt::QuietBrokenPipe quiet;
    (void)std::fputs((line + "\n").c_str(), stderr);
}

// "<scene>:<line>: error: OUTPUT ..." for the scene's OUTPUT, "raytracer.exe: error:
// -o ..." for the user's.
int cannot_write(const std::string& scene_file, const rt::Scene& scene, const rt::OutputChoice& output,
                 const std::string& what) {
    if (output.named_by_user)
        say("raytracer.exe: error: -o " + what);
    else
        say(rt::escaped(rt::scene_name(scene_file)) + ":" + std::to_string(scene.output_line) +
            ": error: OUTPUT " + what);
    return kCannotWrite;
}

// Standard streams that whoever started the program closed (2>&-) are held open on the
// root folder, read-only, so that no file the program opens takes their numbers (the
// image opened as descriptor 2 would receive the progress line meant for standard
// error), while writing to them still fails as it did when closed: -o - >&- is an
// error, not an image sent nowhere. Best effort: where it cannot, they stay closed.
void keep_standard_streams_apart() {
#ifndef _WIN32
    for (int stream = 0; stream <= 2; ++stream)
        if (::fcntl(stream, F_GETFD) < 0 && errno == EBADF && ::open("/", O_RDONLY | O_DIRECTORY) < 0) return;
#endif
}

// The scene rendered into its output (chosen, checked, then replaced only when complete):
// the exit status.
int write_image(const rt::CommandLine& command, const rt::Scene& scene) {
    const rt::OutputChoice output =
        rt::choose_output(scene.output, command.output_given ? &command.output : nullptr, command.scene_file);
    if (!output.refusal.empty()) return cannot_write(command.scene_file, scene, output, output.refusal);
    if (output.destination == rt::Destination::StandardOutput && rt::is_terminal(stdout)) {
        return cannot_write(command.scene_file, scene, output,
                            rt::shown(output.path, rt::kMaxShownPath) +
                                " is a terminal, expected a pipe or a file for a binary image");
    }
    // -o - > f.ppm 2>&1 --progress (or 2>&1 | ..., or -o /dev/fd/3 3>&2): the progress line
    // would go into the image.
    const int stream = output.destination == rt::Destination::StandardOutput ? 1
                       : output.destination == rt::Destination::Descriptor   ? output.descriptor
                                                                             : -1;
    if (stream >= 0 && command.progress == rt::CommandLine::Progress::Always &&
        rt::standard_streams_are_one_stream(stream, 2)) {
        return cannot_write(command.scene_file, scene, output,
                            rt::shown(output.path, rt::kMaxShownPath) +
                                " is also standard error, where --progress draws its line, expected "
                                "another file for the image");
    }
    // The file is created before the render, so that an unwritable OUTPUT is reported
    // before the render is spent on it; nothing of it is left on any error. A scene's
    // OUTPUT stays where choose_output() found it, in the working folder.
    rt::PendingFile file(output.path.c_str(), output.destination, !output.named_by_user, output.descriptor);
    std::string error = file.error();
    if (error.empty()) {
        // The rows are written while later rows render (render.h).
        rt::P6Writer writer(file, scene.columns, scene.rows);
        const bool progress =
            command.progress == rt::CommandLine::Progress::Always ||
            (command.progress == rt::CommandLine::Progress::WhenTerminal && rt::is_terminal(stderr));
        rt::ProgressSink sink(writer, scene.rows, progress);
        if (command.reference)
            rt::render_reference_to<double>(scene, sink, command.threads);
        else
            rt::render_to<double>(scene, sink, command.threads);
        rt::HelperPool::retire();  // the last job of this process
        sink.clear_line();
        error = writer.commit();
    }
    if (!error.empty())
        return cannot_write(command.scene_file, scene, output, error + ", expected a writable file path");
    return kSuccess;
}

}  // namespace

int main(int argc, char** argv) {
    const rt::CommandLine command = rt::parse_command_line(argc, argv);
    if (command.action == rt::CommandLine::Action::Help ||
        command.action == rt::CommandLine::Action::Version) {
        const std::string text = command.action == rt::CommandLine::Action::Help
                                     ? std::string(usage_text())
                                     : std::string("raytracer.exe ") + rt::kVersion + "\n";
        std::fputs(text.c_str(), stdout);
        // A full disk or a closed stdout is an error, not a silent success.
        if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
            say(std::string("raytracer.exe: error: standard output could not be written: ") +
                std::strerror(errno));
            return kCannotWrite;
        }
        return kSuccess;
    }
    if (command.action == rt::CommandLine::Action::Wrong) {
        // One line on stderr (graders collect them): a pointer to --help, not the text.
        say("raytracer.exe: error: " + command.error + " (see --help)");
        return kBadUsage;
    }
    keep_standard_streams_apart();
    rt::install_interrupt_handlers();  // reading a large scene takes a while too
    const std::string shown_file = rt::shown(rt::scene_name(command.scene_file), rt::kMaxShownPath);
    // The scene's size, kept for a message about running out of memory while rendering it.
    struct Size {
        bool known = false;
        int columns = 0, rows = 0;
        std::size_t ellipsoids = 0, lights = 0;
    } size;
    try {
        rt::Scene scene = rt::load_scene(command.scene_file, command.threads);
        rt::bring_lengths_near_one(scene);  // a scene drawn at 1e160 renders as at 1
        size = {true, scene.columns, scene.rows, scene.spheres.size(), scene.lights.size()};
        return write_image(command, scene);
    } catch (const rt::SceneError& e) {
        say(e.what());
        return kBadScene;
    } catch (const std::bad_alloc&) {
        if (!size.known) {
            say("raytracer.exe: error: out of memory reading " + shown_file +
                ", expected a smaller scene file");
        } else {
            say("raytracer.exe: error: out of memory rendering " + shown_file + " (RES " +
                std::to_string(size.columns) + " " + std::to_string(size.rows) + ", " +
                rt::plural(static_cast<long long>(size.ellipsoids), "ellipsoid", "ellipsoids") + ", " +
                rt::plural(static_cast<long long>(size.lights), "light", "lights") +
                "), expected a smaller scene" +
                // Each thread holds a band of rows: more threads than cores cost memory, not time.
                (command.threads > rt::available_cores() ? " or fewer --threads" : ""));
        }
        return kOutOfMemory;
    } catch (const std::exception& e) {
        // Nothing here is expected to throw anything else; still, fail with one line
        // rather than through std::terminate.
        say("raytracer.exe: error: internal error on " + shown_file + ": " + rt::escaped(e.what()));
        return kInternalError;
    }
}
