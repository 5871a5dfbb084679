// The program's command-line contract, tested on the real raytracer.exe as a grading
// script runs it (std::system, through cmd.exe on Windows and Wine): --help and
// --version, the exit statuses main.cpp documents, `raytracer.exe scene.txt` writing
// the image silently, and the atomic replacement of an existing output file (which on
// Windows goes through MoveFileExW).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "process_scratch.h"
#include "raytracer/image.h"
#include "raytracer/ppm.h"
#include "raytracer/version.h"
#include "run_program.h"

#ifndef RAYTRACER_EXE
#error "RAYTRACER_EXE must name the raytracer.exe under test"
#endif

namespace fs = std::filesystem;
using namespace process_scratch;

namespace {

using Run = run_program::Result;

// Runs raytracer.exe with these arguments in the folder, as a grading script does (its
// standard input from the file `input` where one is named). Its output is read as text:
// a Windows program's "\r\n" counts as "\n".
Run run(const Scratch& folder, const std::vector<std::string>& arguments, const fs::path& input = {}) {
    Run r = run_program::run(RAYTRACER_EXE, arguments, folder.work, folder.root, input);
    for (std::string* text : {&r.out, &r.err})
        text->erase(std::remove(text->begin(), text->end(), '\r'), text->end());
    return r;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// No ellipsoid: every pixel is BACK, 0.5 0.25 1 -> 127 63 255 (SPEC section 6).
std::string empty_scene(const std::string& output) {
    return "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES 4 3\n"
           "BACK 0.5 0.25 1\nAMBIENT 0.2 0.2 0.2\nOUTPUT " +
           output + "\n";
}

void check_is_background_image(const fs::path& file) {
    rt::Image image;
    std::string error;
    CHECK(rt::read_ppm(file.string(), image, error));
    CHECK_EQ(image.width, 4);
    CHECK_EQ(image.height, 3);
    CHECK_EQ(image.rgb.size(), std::size_t{36});  // 4 x 3 pixels, 3 bytes each
    for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
        CHECK_EQ(int{image.rgb[i]}, 127);
        CHECK_EQ(int{image.rgb[i + 1]}, 63);
        CHECK_EQ(int{image.rgb[i + 2]}, 255);
    }
    CHECK_EQ(read_bytes(file).substr(0, 11), std::string("P6\n4 3\n255\n"));
}

}  // namespace

TEST(help_prints_usage_on_stdout_and_exits_0) {
    const Scratch folder;
    for (const char* option : {"--help", "-h"}) {
        const Run r = run(folder, {option});
        CHECK_EQ(r.status, 0);
        CHECK(contains(r.out, "usage: raytracer.exe [options] <scene-file>\n"));
        CHECK(contains(r.out, "-o PATH, --output PATH"));
        CHECK(contains(r.out, "no absolute path, no '..'"));
        CHECK(contains(r.out, "SPHERE name x y z sx sy sz r g b Ka Kd Ks Kr n"));
        CHECK(contains(r.out, "Exit status: 0 written; 1 bad scene file; 2 bad command line;"));
        CHECK(contains(r.out, "A scene file of - is read from standard input."));
        CHECK_EQ(r.err, std::string());
        std::istringstream lines(r.out);  // it fits a terminal of 80 columns
        for (std::string line; std::getline(lines, line);) CHECK(line.size() <= 80);
    }
    CHECK(folder.names().empty());
}

TEST(version_prints_the_version_and_exits_0) {
    const Scratch folder;
    const Run r = run(folder, {"--version"});
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out, std::string("raytracer.exe ") + rt::kVersion + "\n");
    CHECK_EQ(r.err, std::string());
}

// One line on stderr that points at --help (graders collect stderr line by line).
TEST(a_wrong_command_line_exits_2_with_one_line_on_stderr) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", empty_scene("picture.ppm"));
    const std::vector<std::pair<std::vector<std::string>, std::string>> wrong = {
        {{}, "no scene file given, expected exactly one scene file"},
        {{"a.txt", "b.txt"}, "more than one argument ('a.txt' and 'b.txt')"},
        {{"--version", "extra"}, "--version with other arguments"},
        {{"--help", "--reference"}, "--help with other arguments"},
        {{"--help", "--version"}, "--help with other arguments"},
        {{""}, "an empty scene file name"},
        {{"--foo", "scene.txt"}, "unknown option '--foo'"},
        {{"scene.txt", "-x"}, "unknown option '-x'"},
        {{"--threads", "0", "scene.txt"}, "--threads '0', expected a whole number from 1 to 1024"},
        {{"scene.txt", "--threads=abc"}, "--threads 'abc'"},
        {{"--threads", "1025", "scene.txt"}, "--threads '1025', expected a whole number from 1 to 1024"},
        {{"--threads", "99999999999999999999999", "scene.txt"}, "--threads '9999999999999999999999"},
        {{"--threads", "+2", "scene.txt"}, "--threads '+2'"},
        {{"scene.txt", "--threads"}, "--threads without a value"},
        {{"scene.txt", "-o"}, "-o without a value"},
        {{"scene.txt", "--output="}, "--output with an empty path"},
        {{"--quiet=1", "scene.txt"}, "'--quiet' takes no value"},
        {{"--thr=2", "scene.txt"}, "unknown option '--thr'"},
        {{"--threads", "2", "scene.txt", "--threads=3"},
         "--threads given twice ('2' and '3'), expected it once"},
        {{"-o", "a.ppm", "scene.txt", "--output", "b.ppm"},
         "-o/--output given twice ('a.ppm' and 'b.ppm'), expected it once"},
        {{"--progress", "scene.txt", "--quiet"},
         "--progress and --quiet together, expected at most one of them"},
    };
    for (const auto& [arguments, message] : wrong) {
        const Run r = run(folder, arguments);
        CHECK_EQ(r.status, 2);
        CHECK_EQ(r.out, std::string());
        CHECK(contains(r.err, "raytracer.exe: error: " + message));
        CHECK(contains(r.err, " (see --help)\n"));
        CHECK_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
    }
    CHECK_EQ(folder.names(), std::string("scene.txt"));
}

// --threads N and --threads=N anywhere, the other options anywhere, and "--" ending them.
TEST(options_go_anywhere_in_either_form) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", empty_scene("picture.ppm"));
    write_bytes(folder.work / "-scene.txt", empty_scene("dash.ppm"));
    const std::vector<std::vector<std::string>> right = {
        {"--threads", "2", "scene.txt"},
        {"scene.txt", "--threads", "2"},
        {"--threads=1", "scene.txt"},
        {"scene.txt", "--quiet"},
        {"--progress", "scene.txt"},
        {"--threads=2", "--", "-scene.txt"},
        {"--threads=00002", "scene.txt"},
        {"--threads", "0000000001024", "scene.txt"}};  // leading zeros, any number
    for (const std::vector<std::string>& arguments : right) {
        const Run r = run(folder, arguments);
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err, std::string());
    }
    check_is_background_image(folder.work / "picture.ppm");
    check_is_background_image(folder.work / "dash.ppm");
}

// -o overrides OUTPUT; -o - writes the same bytes to standard output (for pipes).
TEST(dash_o_overrides_output_and_dash_is_standard_output) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", empty_scene("picture.ppm"));
    Run r = run(folder, {"scene.txt", "-o", "other.ppm"});
    CHECK_EQ(r.status, 0);
    check_is_background_image(folder.work / "other.ppm");
    CHECK_EQ(folder.names(), std::string("other.ppm scene.txt"));
    r = run(folder, {"--output=third.ppm", "scene.txt"});
    CHECK_EQ(r.status, 0);
    check_is_background_image(folder.work / "third.ppm");
    // Read raw: the image's bytes, not text.
    const Run piped = run_program::run(RAYTRACER_EXE, {"-o", "-", "scene.txt"}, folder.work, folder.root);
    CHECK_EQ(piped.status, 0);
    CHECK_EQ(piped.err, std::string());
    CHECK(piped.out == read_bytes(folder.work / "other.ppm"));
    CHECK_EQ(folder.names(), std::string("other.ppm scene.txt third.ppm"));
}

// The scene file "-" is standard input: the same image, and messages that call it <stdin>.
// The file standard input is may not be the image, as the scene file may not.
TEST(dash_reads_the_scene_from_standard_input) {
    const Scratch folder;
    write_bytes(folder.root / "scene.txt", empty_scene("picture.ppm"));
    Run r = run(folder, {"-"}, folder.root / "scene.txt");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err, std::string());
    check_is_background_image(folder.work / "picture.ppm");
    write_bytes(folder.root / "bad.txt", "NEAR 1\nRES 4 3\nFOO 1\n");
    r = run(folder, {"-"}, folder.root / "bad.txt");
    CHECK_EQ(r.status, 1);
    CHECK(contains(r.err, "<stdin>:3: error: unknown keyword 'FOO'"));
    write_bytes(folder.root / "empty.txt", "");
    r = run(folder, {"--threads", "1", "-"}, folder.root / "empty.txt");
    CHECK_EQ(r.status, 1);
    CHECK_EQ(r.err, std::string("<stdin>: error: is empty, expected a scene file\n"));
    write_bytes(folder.work / "self.txt", empty_scene("self.txt"));
    r = run(folder, {"-"}, folder.work / "self.txt");
    CHECK_EQ(r.status, 3);
    CHECK(contains(r.err, "<stdin>:9: error: OUTPUT 'self.txt' is the scene file itself"));
    CHECK_EQ(read_bytes(folder.work / "self.txt"), empty_scene("self.txt"));
    write_bytes(folder.work / "-", empty_scene("named.ppm"));  // a file named "-": ./-
    r = run(folder, {"./-"});
    CHECK_EQ(r.status, 0);
    check_is_background_image(folder.work / "named.ppm");
    CHECK_EQ(folder.names(), std::string("- named.ppm picture.ppm self.txt"));
}

// A scene may name only a file in or below the working folder; -o may name any.
TEST(a_scene_may_not_write_outside_the_working_folder) {
    const Scratch folder;
    const fs::path outside = folder.root / "outside.ppm";
    const std::vector<std::pair<std::string, std::string>> refused = {
        {outside.string(), "is an absolute path, expected a file name in or below the working folder"},
        {"../outside.ppm", "leaves the working folder ('..')"},
        {"sub/../../outside.ppm", "leaves the working folder ('..')"},
        {"scene.txt", "'scene.txt' is the scene file itself"},
        {"./scene.txt", "is the scene file itself"},
#ifdef _WIN32
        {"C:outside.ppm",
         "'C:outside.ppm' names a drive, expected a file name in or below the working folder"},
#endif
    };
    fs::create_directories(folder.work / "sub");
    for (const auto& [output, message] : refused) {
        const std::string scene = empty_scene(output);
        write_bytes(folder.work / "scene.txt", scene);
        const Run r = run(folder, {"scene.txt"});
        CHECK_EQ(r.status, 3);
        CHECK(contains(r.err, "scene.txt:9: error: OUTPUT "));
        CHECK(contains(r.err, message));
        CHECK_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
        CHECK(!fs::exists(outside));
        CHECK_EQ(read_bytes(folder.work / "scene.txt"), scene);
        CHECK_EQ(folder.names(), std::string("scene.txt sub"));
    }
    // The user may: -o takes any path, but never the scene file.
    write_bytes(folder.work / "scene.txt", empty_scene(outside.string()));
    Run r = run(folder, {"scene.txt", "-o", outside.string()});
    CHECK_EQ(r.status, 0);
    check_is_background_image(outside);
    r = run(folder, {"scene.txt", "-o", "scene.txt"});
    CHECK_EQ(r.status, 3);
    CHECK(contains(r.err, "raytracer.exe: error: -o 'scene.txt' is the scene file itself"));
    CHECK(contains(read_bytes(folder.work / "scene.txt"), "OUTPUT"));
}

// Control bytes and long values in a path reach the terminal escaped and cut.
TEST(paths_in_messages_are_escaped_and_cut) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", empty_scene("\x1b]0;title\x07/" + std::string(5000, 'x')));
    const Run r = run(folder, {"scene.txt"});
    CHECK_EQ(r.status, 3);
    CHECK(contains(r.err, "OUTPUT '\\x1b]0;title\\x07/xxx"));
    CHECK(contains(r.err, "(5011 bytes)"));
    CHECK(r.err.find('\x1b') == std::string::npos);
    CHECK(r.err.size() < 600);
#ifndef _WIN32  // cmd.exe cannot pass a control byte
    const Run missing = run(folder, {std::string("no\x01such-") + std::string(3000, 'y') + ".txt"});
    CHECK_EQ(missing.status, 1);
    CHECK(contains(missing.err, "no\\x01such-yyy"));
    CHECK(missing.err.size() < 600);
#endif
    // Every \x shown starts an escape: a backslash before an x is escaped too, so that the
    // text "\x1b" and an ESC byte read apart; other backslashes show as they are.
    write_bytes(folder.work / "scene.txt", empty_scene("a\\x1b/"));
    CHECK(contains(run(folder, {"scene.txt"}).err, "OUTPUT 'a\\x5cx1b/'"));
    write_bytes(folder.work / "scene.txt", empty_scene("a\\\x1b\\b/"));
    CHECK(contains(run(folder, {"scene.txt"}).err, "OUTPUT 'a\\\\x1b\\b/'"));
}

// --reference renders through the reference path (every ray against every ellipsoid):
// the same bytes as the fast path, here on a scene with shadows and mirrors.
TEST(reference_renders_the_same_bytes_as_the_fast_path) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt",
                "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES 48 36\n"
                "SPHERE floor 0 -3 -10 20 1 20 0.5 0.5 0.5 0.2 0.6 0.3 0.4 10\n"
                "SPHERE ball -1 0 -8 1 1.5 1 1 0.2 0.1 0.3 0.7 0.5 0.5 50\n"
                "SPHERE egg 1.5 0.5 -9 1.2 0.6 0.8 0.1 0.8 0.3 0.3 0.6 0.9 0 20\n"
                "LIGHT key 4 6 -2 0.8 0.8 0.8\nLIGHT fill -6 2 -4 0.3 0.3 0.5\n"
                "BACK 0.1 0.1 0.2\nAMBIENT 0.3 0.3 0.3\nOUTPUT fast.ppm\n");
    CHECK_EQ(run(folder, {"scene.txt"}).status, 0);
    for (const std::vector<std::string>& arguments :
         {std::vector<std::string>{"--reference", "scene.txt", "-o", "reference.ppm"},
          std::vector<std::string>{"scene.txt", "--threads=3", "--reference", "-o", "reference.ppm"}}) {
        const Run r = run(folder, arguments);
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err, std::string());
        CHECK(read_bytes(folder.work / "reference.ppm") == read_bytes(folder.work / "fast.ppm"));
    }
    // Not an image of the background (25 25 51) alone: the ellipsoids are in it.
    const std::string bytes = read_bytes(folder.work / "fast.ppm");
    CHECK_EQ(bytes.size(), std::size_t{13 + 48 * 36 * 3});
    int background = 0;
    for (std::size_t i = 13; i + 2 < bytes.size(); i += 3)
        background += bytes.compare(i, 3, "\x19\x19\x33") == 0 ? 1 : 0;
    CHECK(background > 0 && background < 48 * 36 * 3 / 4);
}

// A scene drawn at 1e160 or 1e-160 (every length so scaled) renders as at 1: its squared
// lengths would overflow or underflow, and raytracer.exe brings it near 1 first
// (scene_scale.h).
TEST(a_scene_of_extreme_size_renders_as_at_its_own) {
    const Scratch folder;
    auto scene = [](const std::string& e, const std::string& output) {
        return "NEAR 1" + e + "\nLEFT -1" + e + "\nRIGHT 1" + e + "\nBOTTOM -1" + e + "\nTOP 1" + e +
               "\nRES 40 40\nSPHERE s 0.5" + e + " 0 -10" + e + " 2" + e + " 3" + e + " 2" + e +
               " 1 0.5 0 0.1 0.8 0.5 0 20\nLIGHT l 3" + e + " 4" + e +
               " 0 1 1 1\nBACK 0 0 1\nAMBIENT 0.2 0.2 "
               "0.2\nOUTPUT " +
               output + "\n";
    };
    write_bytes(folder.work / "one.txt", scene("", "one.ppm"));
    write_bytes(folder.work / "huge.txt", scene("e160", "huge.ppm"));
    write_bytes(folder.work / "tiny.txt", scene("e-160", "tiny.ppm"));
    // A coordinate far below the scene's size (a centre's y of 1e-240 at 1e160) does not
    // keep the scene from its shift: it counts as the 0 it is beside the others.
    std::string spanning = scene("e160", "spanning.ppm");
    spanning.replace(spanning.find(" 0 -10e160"), 10, " 1e-240 -10e160");
    write_bytes(folder.work / "spanning.txt", spanning);
    for (const char* file : {"one.txt", "huge.txt", "tiny.txt", "spanning.txt"})
        CHECK_EQ(run(folder, {file}).status, 0);
    const std::string one = read_bytes(folder.work / "one.ppm");
    CHECK(one == read_bytes(folder.work / "huge.ppm"));
    CHECK(one == read_bytes(folder.work / "tiny.ppm"));
    CHECK(one == read_bytes(folder.work / "spanning.ppm"));
    CHECK(one.find("\xff\x80") != std::string::npos);  // lit: red 255, green 128 somewhere

    // A light at 1e300 beside a speck of scale 1e-10: no shift holds both squares, and
    // the light's is kept from overflowing (it lit nothing when it did): the bytes of the
    // light at 1e250, which needs no shift.
    auto far_light = [](const std::string& z) {
        return "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES 20 20\n"
               "SPHERE ball 0 0 -5 1 1 1 1 1 1 0.1 0.9 0 0 1\nLIGHT sun 0 0 " +
               z +
               " 1 1 1\nSPHERE speck 50 0 -5 1e-10 1e-10 1e-10 1 1 1 0 0 0 0 1\nBACK 0 0 0\n"
               "AMBIENT 1 1 1\nOUTPUT far.ppm\n";
    };
    write_bytes(folder.work / "far.txt", far_light("1e300"));
    CHECK_EQ(run(folder, {"far.txt"}).status, 0);
    const std::string farthest = read_bytes(folder.work / "far.ppm");
    write_bytes(folder.work / "far.txt", far_light("1e250"));
    CHECK_EQ(run(folder, {"far.txt"}).status, 0);
    CHECK(farthest == read_bytes(folder.work / "far.ppm"));
    CHECK(farthest.find("\xff\xff\xff") != std::string::npos);  // lit: 0.1 + 0.9 facing the light
}

TEST(a_scene_renders_silently_to_its_output_file) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", empty_scene("picture.ppm"));
    const Run r = run(folder, {"scene.txt"});
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out, std::string());
    CHECK_EQ(r.err, std::string());
    check_is_background_image(folder.work / "picture.ppm");
    CHECK_EQ(folder.names(), std::string("picture.ppm scene.txt"));
}

TEST(an_existing_output_file_is_replaced_whole) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", empty_scene("picture.ppm"));
    // Longer than the new image, so a write in place without truncation would show.
    const std::string old_bytes(1000, 'x');
    write_bytes(folder.work / "picture.ppm", old_bytes);
    // A second name for the old file: the image is written to a file of its own and put
    // in the old one's place at once, so the old file, never rewritten, keeps its bytes.
    fs::create_hard_link(folder.work / "picture.ppm", folder.work / "old.ppm");
    for (int pass = 0; pass < 2; ++pass) {  // replacing the program's own output as well
        const Run r = run(folder, {"scene.txt"});
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err, std::string());
        check_is_background_image(folder.work / "picture.ppm");
        CHECK_EQ(read_bytes(folder.work / "picture.ppm").size(), std::size_t{11 + 36});
        CHECK(read_bytes(folder.work / "old.ppm") == old_bytes);
        // No temporary file left beside it.
        CHECK_EQ(folder.names(), std::string("old.ppm picture.ppm scene.txt"));
    }
}

TEST(a_bad_scene_exits_1_and_leaves_an_existing_output_alone) {
    const Scratch folder;
    write_bytes(folder.work / "bad.txt", empty_scene("picture.ppm") + "CUBE 1 2 3\n");
    write_bytes(folder.work / "picture.ppm", "old");
    const Run r = run(folder, {"bad.txt"});
    CHECK_EQ(r.status, 1);
    CHECK_EQ(r.out, std::string());
    CHECK(contains(r.err, "bad.txt"));
    CHECK(contains(r.err, "CUBE"));
    CHECK_EQ(read_bytes(folder.work / "picture.ppm"), std::string("old"));
    CHECK_EQ(folder.names(), std::string("bad.txt picture.ppm"));
}

TEST(a_missing_scene_file_exits_1) {
    const Scratch folder;
    const Run r = run(folder, {"no-such-scene.txt"});
    CHECK_EQ(r.status, 1);
    CHECK(contains(r.err, "no-such-scene.txt"));
    CHECK(folder.names().empty());
}

TEST(an_unwritable_output_exits_3_and_writes_nothing) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", empty_scene("missing-folder/picture.ppm"));
    const Run r = run(folder, {"scene.txt"});
    CHECK_EQ(r.status, 3);
    CHECK(contains(r.err, "missing-folder/picture.ppm"));
    CHECK_EQ(folder.names(), std::string("scene.txt"));
}
