// The program's command-line contract, tested on the real raytracer.exe as a grading
// script runs it (std::system, through cmd.exe on Windows and Wine): --help and
// --version, the exit statuses main.cpp documents, `raytracer.exe scene.txt` writing
// the image silently, and the atomic replacement of an existing output file (which on
// Windows goes through MoveFileExW).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "raytracer/image.h"
#include "raytracer/ppm.h"
#include "raytracer/version.h"
#include "run_program.h"

#ifndef RAYTRACER_EXE
#error "RAYTRACER_EXE must name the raytracer.exe under test"
#endif

namespace fs = std::filesystem;

namespace {

// A fresh, empty working folder per test, inside a root of its own that also holds
// the captured output; both removed afterwards.
class Scratch {
public:
    Scratch() {
        std::random_device random;
        root_ = fs::temp_directory_path() / ("raytracer-cli-" + std::to_string(random()));
        path_ = root_ / "work";
        fs::create_directories(path_);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    ~Scratch() {
        std::error_code ignored;
        fs::remove_all(root_, ignored);
    }
    [[nodiscard]] const fs::path& path() const { return path_; }
    [[nodiscard]] const fs::path& root() const { return root_; }
    [[nodiscard]] fs::path operator/(const std::string& name) const { return path_ / name; }

    // The names in the folder, sorted, separated by spaces.
    [[nodiscard]] std::string names() const {
        std::vector<std::string> all;
        for (const fs::directory_entry& entry : fs::directory_iterator(path_))
            all.push_back(entry.path().filename().string());
        std::sort(all.begin(), all.end());
        std::string joined;
        for (const std::string& name : all) joined += (joined.empty() ? "" : " ") + name;
        return joined;
    }

private:
    fs::path root_, path_;
};

std::string read_bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& file, const std::string& bytes) {
    std::ofstream out(file, std::ios::binary);
    out << bytes;
}

using Run = run_program::Result;

// Runs raytracer.exe with these arguments in the folder, as a grading script does.
// Its output is read as text: a Windows program's "\r\n" counts as "\n".
Run run(const Scratch& folder, const std::vector<std::string>& arguments) {
    Run r = run_program::run(RAYTRACER_EXE, arguments, folder.path(), folder.root());
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
        CHECK(contains(r.out, "usage: raytracer.exe [--threads N] <scene-file>\n"));
        CHECK(contains(r.out, "SPHERE name x y z sx sy sz r g b Ka Kd Ks Kr n"));
        CHECK(contains(r.out, "Exit status: 0 written; 1 bad scene file; 2 bad command line;"));
        CHECK_EQ(r.err, std::string());
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
    const std::vector<std::vector<std::string>> wrong = {
        {}, {"a.txt", "b.txt"}, {"--version", "extra"}, {""}};
    for (const std::vector<std::string>& arguments : wrong) {
        const Run r = run(folder, arguments);
        CHECK_EQ(r.status, 2);
        CHECK_EQ(r.out, std::string());
        CHECK(contains(r.err, "raytracer.exe: error: "));
        CHECK(contains(r.err, "expected exactly one scene file (see --help)\n"));
        CHECK_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
    }
}

TEST(a_scene_renders_silently_to_its_output_file) {
    const Scratch folder;
    write_bytes(folder / "scene.txt", empty_scene("picture.ppm"));
    const Run r = run(folder, {"scene.txt"});
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out, std::string());
    CHECK_EQ(r.err, std::string());
    check_is_background_image(folder / "picture.ppm");
    CHECK_EQ(folder.names(), std::string("picture.ppm scene.txt"));
}

TEST(an_existing_output_file_is_replaced_whole) {
    const Scratch folder;
    write_bytes(folder / "scene.txt", empty_scene("picture.ppm"));
    // Longer than the new image, so a write in place without truncation would show.
    write_bytes(folder / "picture.ppm", std::string(1000, 'x'));
    for (int pass = 0; pass < 2; ++pass) {  // replacing the program's own output as well
        const Run r = run(folder, {"scene.txt"});
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err, std::string());
        check_is_background_image(folder / "picture.ppm");
        CHECK_EQ(read_bytes(folder / "picture.ppm").size(), std::size_t{11 + 36});
        // No temporary file left beside it.
        CHECK_EQ(folder.names(), std::string("picture.ppm scene.txt"));
    }
}

TEST(a_bad_scene_exits_1_and_leaves_an_existing_output_alone) {
    const Scratch folder;
    write_bytes(folder / "bad.txt", empty_scene("picture.ppm") + "CUBE 1 2 3\n");
    write_bytes(folder / "picture.ppm", "old");
    const Run r = run(folder, {"bad.txt"});
    CHECK_EQ(r.status, 1);
    CHECK_EQ(r.out, std::string());
    CHECK(contains(r.err, "bad.txt"));
    CHECK(contains(r.err, "CUBE"));
    CHECK_EQ(read_bytes(folder / "picture.ppm"), std::string("old"));
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
    write_bytes(folder / "scene.txt", empty_scene("missing-folder/picture.ppm"));
    const Run r = run(folder, {"scene.txt"});
    CHECK_EQ(r.status, 3);
    CHECK(contains(r.err, "missing-folder/picture.ppm"));
    CHECK_EQ(folder.names(), std::string("scene.txt"));
}
