// The bad-input test: runs raytracer.exe on every scene of tests/bad (listed with the
// refusal it must get in tests/bad/MANIFEST) and on the command-line mistakes below,
// and checks each error as a grading script would see it:
//   - the exit status;
//   - exactly one line on stderr, "<file>:<line>: error: ..." (no ":<line>" when the
//     manifest says 0) containing the expected fragment, and nothing on stdout;
//   - out.ppm, created beforehand in the working folder, byte-identical afterwards;
//   - no other file left in the working folder (no temporary, no partial image).
//
//   bad_input <raytracer.exe> <tests/bad folder>
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "raytracer/image.h"
#include "raytracer/ppm.h"
#include "run_program.h"

#ifndef _WIN32
#include <unistd.h>  // geteuid: permission tests mean nothing to root
#endif

namespace fs = std::filesystem;

namespace {

struct Expected {
    std::string file;
    int status = 0;
    int line = 0;  // 0: the message names no line
    std::string fragment;
};

// A command line to try and the refusal it must get.
struct Case {
    std::string name;
    std::vector<std::string> args;
    Expected expected;
    std::string error_file;  // the file name the message must start with; empty: "raytracer.exe"
};

const std::string kPrecious = "an existing out.ppm that no failed run may touch\n";

int failures = 0;
int cases_run = 0;

void expect(bool ok, const std::string& name, const std::string& what) {
    if (ok) return;
    ++failures;
    std::cout << "FAIL  " << name << ": " << what << "\n";
}

std::string trim(const std::string& s) {
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::vector<Expected> read_manifest(const fs::path& path) {
    std::vector<Expected> entries;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> parts;
        std::size_t start = 0;
        for (int i = 0; i < 3; ++i) {
            const std::size_t bar = line.find('|', start);
            if (bar == std::string::npos) break;
            parts.push_back(trim(line.substr(start, bar - start)));
            start = bar + 1;
        }
        if (parts.size() != 3) {
            expect(false, "MANIFEST", "malformed line: " + line);
            continue;
        }
        entries.push_back({parts[0], std::stoi(parts[1]), std::stoi(parts[2]), trim(line.substr(start))});
    }
    return entries;
}

std::vector<std::string> folder_listing(const fs::path& folder) {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
        names.push_back(entry.path().filename().u8string());
    std::sort(names.begin(), names.end());
    return names;
}

void write_file(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// Runs one case in a fresh working folder holding only out.ppm, and checks everything.
void run_case(const fs::path& raytracer, const fs::path& scratch, const Case& c) {
    ++cases_run;
    const int failures_before = failures;
    const fs::path box = scratch / c.name, work = box / "work";
    fs::create_directories(work);
    write_file(work / "out.ppm", kPrecious);

    const run_program::Result r = run_program::run(raytracer, c.args, work, box);
    const Expected& e = c.expected;
    expect(r.status == e.status, c.name,
           "exit status " + std::to_string(r.status) + ", expected " + std::to_string(e.status) +
               " (stderr: " + r.err + ")");
    expect(r.out.empty(), c.name, "wrote to stdout: " + r.out);

    if (e.status == 0) {
        expect(r.err.empty(), c.name, "wrote to stderr: " + r.err);
        rt::Image image;
        std::string error;
        expect(rt::read_ppm((work / "out.ppm").string(), image, error), c.name, "no image written: " + error);
    } else {
        const bool one_line =
            !r.err.empty() && r.err.back() == '\n' && std::count(r.err.begin(), r.err.end(), '\n') == 1;
        expect(one_line, c.name, "stderr is not exactly one line: " + r.err);
        const std::string file = c.error_file.empty() ? "raytracer.exe" : c.error_file;
        const std::string prefix = file + (e.line > 0 ? ":" + std::to_string(e.line) : "") + ": error: ";
        expect(r.err.rfind(prefix, 0) == 0, c.name, "message does not start with '" + prefix + "': " + r.err);
        expect(r.err.find(e.fragment) != std::string::npos, c.name,
               "message lacks '" + e.fragment + "': " + r.err);
        expect(run_program::read_file(work / "out.ppm") == kPrecious, c.name, "out.ppm was changed");
    }
    const std::vector<std::string> left = folder_listing(work);
    expect(left == std::vector<std::string>{"out.ppm"}, c.name,
           "the working folder holds " + std::to_string(left.size()) + " files, expected out.ppm only");
    if (failures == failures_before) std::cout << "ok    " << c.name << "\n";
}

#ifndef _WIN32
bool running_as_root() { return geteuid() == 0; }
#endif

// Bytes 1..255 in a fixed pseudo-random order: binary, but without the NUL byte that
// load_scene spots first, so the parser itself must cope.
std::string binary_without_nul(std::size_t size) {
    std::minstd_rand random(42);
    std::string bytes;
    for (std::size_t i = 0; i < size; ++i) bytes += static_cast<char>(1 + random() % 255);
    return bytes;
}

// The corpus of tests/bad: every scene listed, every listed scene present, at least 40.
void corpus_cases(const fs::path& raytracer, const fs::path& bad, const fs::path& scratch) {
    const std::vector<Expected> manifest = read_manifest(bad / "MANIFEST");
    expect(manifest.size() >= 40, "MANIFEST",
           "lists " + std::to_string(manifest.size()) + " scenes, expected 40+");
    for (const fs::directory_entry& entry : fs::directory_iterator(bad)) {
        const std::string name = entry.path().filename().u8string();
        const bool listed =
            std::any_of(manifest.begin(), manifest.end(), [&](const Expected& e) { return e.file == name; });
        expect(name == "MANIFEST" || name[0] == '.' || listed, "MANIFEST", name + " is not listed");
    }
    for (const Expected& e : manifest) {
        const std::string path = (bad / e.file).string();
        run_case(raytracer, scratch, {e.file, {path}, e, path});
    }
    // output_absolute.txt names a file outside the working folder, output_dot_dot.txt
    // the folder above it: neither may appear.
    expect(!fs::exists("/tmp/raytracer-bad-input-absolute.ppm"), "output_absolute.txt",
           "the file was written");
    expect(!fs::exists(scratch / "output_dot_dot.txt" / "out.ppm"), "output_dot_dot.txt",
           "the file was written");
}

// The command line, and files that are not scene files at all.
void command_line_cases(const fs::path& raytracer, const fs::path& bad, const fs::path& scratch) {
    const std::string good = (bad / "control_good.txt").string();
    const std::string good_text = run_program::read_file(good);
    run_case(raytracer, scratch, {"no-argument", {}, {"", 2, 0, "no scene file given"}, ""});
    run_case(raytracer, scratch, {"two-arguments", {good, good}, {"", 2, 0, "more than one argument"}, ""});
    run_case(raytracer, scratch,
             {"unknown-option", {"--foo", good}, {"", 2, 0, "unknown option '--foo'"}, ""});
    run_case(raytracer, scratch, {"threads-after-the-scene", {good, "--threads", "2"}, {"", 0, 0, ""}, ""});
    run_case(raytracer, scratch, {"threads-with-equals", {"--threads=2", good}, {"", 0, 0, ""}, ""});

    run_case(raytracer, scratch, {"empty-argument", {""}, {"", 2, 0, "an empty scene file name"}, ""});
    const std::string missing = (scratch / "no-such-scene.txt").string();
    run_case(raytracer, scratch, {"missing-file", {missing}, {"", 1, 0, "does not exist"}, missing});
    run_case(
        raytracer, scratch,
        {"folder-as-scene", {bad.string()}, {"", 1, 0, "is a folder, expected a scene file"}, bad.string()});

    const std::string long_token = (scratch / "long-token.txt").string();
    write_file(long_token, std::string(200'000, 'A') + "\n");
    run_case(raytracer, scratch,
             {"200KB-token", {long_token}, {"", 1, 1, "...' (200000 bytes), expected one of"}, long_token});
    const std::string long_number = (scratch / "long-number.txt").string();
    write_file(long_number,
               "NEAR " + std::string(200'000, '9') + "\n" + good_text.substr(good_text.find('\n') + 1));
    run_case(raytracer, scratch,
             {"200KB-number", {long_number}, {"", 1, 1, "expected a finite decimal number"}, long_number});

    const std::string binary = (scratch / "binary.bin").string();
    write_file(binary, "\x89PNG\r\n\x1a\n" + binary_without_nul(4096));
    run_case(raytracer, scratch,
             {"binary-without-nul", {binary}, {"", 1, 1, "unknown keyword '\\x89PNG'"}, binary});
    const std::string binary_nul = (scratch / "binary-nul.bin").string();
    write_file(binary_nul, std::string("\x7f"
                                       "ELF\x02\x01\x01\x00\x00",
                                       9) +
                               binary_without_nul(4096));
    run_case(raytracer, scratch, {"binary-with-nul", {binary_nul}, {"", 1, 1, "a NUL byte"}, binary_nul});

#ifndef _WIN32
    // An endless file must be refused after a bounded read, not read into memory forever.
    run_case(raytracer, scratch,
             {"endless-file",
              {"/dev/zero"},
              {"", 1, 0, "is larger than 64 MiB, expected a scene file"},
              "/dev/zero"});
#endif
}

// Files this user may not read or write (POSIX permissions). Root may read and write
// anything, so these say nothing when run as root (as CI does); the same refusals are
// covered as root by output_under_a_file and output_missing_folder in the corpus.
void permission_cases(const fs::path& raytracer, const fs::path& bad, const fs::path& scratch) {
#ifdef _WIN32
    (void)raytracer, (void)bad, (void)scratch;
#else
    if (running_as_root()) {
        std::cout << "skip  unreadable-file, read-only-folder: running as root, permissions do not apply\n";
        return;
    }
    const std::string good = (bad / "control_good.txt").string();
    const std::string good_text = run_program::read_file(good);
    const fs::path unreadable = scratch / "unreadable.txt";
    write_file(unreadable, good_text);
    fs::permissions(unreadable, fs::perms::none);
    run_case(raytracer, scratch,
             {"unreadable-file",
              {unreadable.string()},
              {"", 1, 0, "cannot be opened for reading"},
              unreadable.string()});
    fs::permissions(unreadable, fs::perms::owner_read | fs::perms::owner_write);

    // control_good.txt writes out.ppm into a working folder that is read-only.
    const fs::path box = scratch / "read-only-folder", work = box / "work";
    fs::create_directories(work);
    write_file(work / "out.ppm", kPrecious);
    fs::permissions(work, fs::perms::owner_read | fs::perms::owner_exec);
    const run_program::Result r = run_program::run(raytracer, {good}, work, box);
    ++cases_run;
    expect(r.status == 3, "read-only-folder", "exit status " + std::to_string(r.status) + ", expected 3");
    expect(r.err.find("its folder is not writable") != std::string::npos, "read-only-folder", r.err);
    expect(run_program::read_file(work / "out.ppm") == kPrecious, "read-only-folder", "out.ppm was changed");
    expect(folder_listing(work).size() == 1, "read-only-folder", "a stray file was left");
    fs::permissions(work, fs::perms::owner_all);
#endif
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: bad_input <raytracer.exe> <tests/bad folder>\n";
        return 2;
    }
    const fs::path raytracer = fs::absolute(argv[1]);
    const fs::path bad = fs::absolute(argv[2]);
    std::mt19937_64 random(std::random_device{}());
    const fs::path scratch = fs::temp_directory_path() / ("raytracer-bad-" + std::to_string(random()));
    fs::create_directories(scratch);

    corpus_cases(raytracer, bad, scratch);
    command_line_cases(raytracer, bad, scratch);
    permission_cases(raytracer, bad, scratch);

    std::error_code ignored;
    fs::remove_all(scratch, ignored);
    std::cout << cases_run << " cases, " << failures << " failed checks\n";
    return failures == 0 ? 0 : 1;
}
