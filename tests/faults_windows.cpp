// Faults around a render on Windows, on the real raytracer.exe started as a child
// process (faults.cpp holds POSIX's): a render killed mid-way (as by Task Manager or a
// closed console window), an image another program holds open, names Windows keeps for
// devices or cannot hold, -o into devices and raw paths, and folder links out of the
// working folder.
#include "check.h"

#include "raytracer/windows_api.h"

#include <string>
#include <utility>
#include <vector>

#include "process_scratch.h"
#include "raytracer/output_file.h"
#include "run_program.h"

#ifndef RAYTRACER_EXE
#error "RAYTRACER_EXE must name the raytracer.exe under test"
#endif

using namespace process_scratch;

namespace {

// Whether the folder holds a temporary of raytracer.exe's (output_file.h).
bool has_temporary(const fs::path& folder) {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
        if (entry.path().filename().string().rfind(std::string(rt::kTemporaryPrefix), 0) == 0) return true;
    return false;
}

#ifndef RAYTRACER_HOST_FOLDER_LINKS
// A symbolic link to a folder (the standard library of MinGW makes none).
bool folder_link(const fs::path& target, const fs::path& link) {
    constexpr DWORD kUnprivileged = 0x2;  // SYMBOLIC_LINK_FLAG_ALLOW_UNPRIVILEGED_CREATE
    return CreateSymbolicLinkW(link.c_str(), target.c_str(), SYMBOLIC_LINK_FLAG_DIRECTORY | kUnprivileged) !=
           0;
}
#endif

// raytracer.exe with these arguments in work, its output captured in root.
run_program::Result run(const fs::path& work, const fs::path& root,
                        const std::vector<std::string>& arguments) {
    return run_program::run(RAYTRACER_EXE, arguments, work, root);
}

}  // namespace

// TerminateProcess runs no code of the program's: only the system can remove the
// temporary, which it deletes when the killed process's handle to it closes.
TEST(a_killed_render_leaves_nothing_behind) {
    const Scratch folder;
    const std::string precious = "an existing out.ppm that a killed run may not touch\n";
    write_bytes(folder.work / "slow.txt", slow_scene("out.ppm"));
    write_bytes(folder.work / "out.ppm", precious);
    // One thread: seconds of render on any machine, far more than the polls below take.
    std::wstring command = L"\"" + fs::path(RAYTRACER_EXE).wstring() + L"\" --quiet --threads 1 slow.txt";
    STARTUPINFOW startup{};
    startup.cb = sizeof startup;
    PROCESS_INFORMATION process{};
    CHECK(CreateProcessW(nullptr, command.data(), nullptr, nullptr, FALSE, 0, nullptr, folder.work.c_str(),
                         &startup, &process));
    if (process.hProcess == nullptr) return;
    bool rendering = false;  // its temporary is there once the scene is read
    for (int wait = 0; wait < 600 && !rendering; ++wait) {
        rendering = has_temporary(folder.work);
        if (!rendering) Sleep(50);
    }
    CHECK(rendering);
    CHECK_EQ(WaitForSingleObject(process.hProcess, 0), DWORD{WAIT_TIMEOUT});  // still rendering
    CHECK(TerminateProcess(process.hProcess, 99));
    CHECK_EQ(WaitForSingleObject(process.hProcess, INFINITE), WAIT_OBJECT_0);
    DWORD status = 0;
    CHECK(GetExitCodeProcess(process.hProcess, &status));
    CHECK_EQ(status, DWORD{99});
    (void)CloseHandle(process.hThread);
    (void)CloseHandle(process.hProcess);
    // The name goes when the last handle to the file closes: a virus scanner's may
    // outlive the process for a moment.
    for (int wait = 0; wait < 40 && has_temporary(folder.work); ++wait) Sleep(50);
    CHECK_EQ(folder.names(), std::string("out.ppm slow.txt"));
    CHECK_EQ(read_bytes(folder.work / "out.ppm"), precious);
}

// An image open in another program without leave to delete it (a viewer): the render's
// file cannot replace it. Exit 3, the system's reason, the image and folder as they were.
TEST(an_image_held_open_by_another_program_is_not_replaced) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    write_bytes(folder.work / "out.ppm", "old");
    const HANDLE held = CreateFileW((folder.work / "out.ppm").c_str(), GENERIC_READ, FILE_SHARE_READ, nullptr,
                                    OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, nullptr);
    CHECK(held != INVALID_HANDLE_VALUE);
    const run_program::Result r = run(folder.work, folder.root, {"scene.txt"});
    (void)CloseHandle(held);
    CHECK_EQ(r.status, 3);
    CHECK(r.err.find("error: OUTPUT 'out.ppm' cannot be replaced: another program may have it open, or it is "
                     "protected (Windows error ") != std::string::npos);
    CHECK_EQ(folder.names(), std::string("out.ppm scene.txt"));
    CHECK_EQ(read_bytes(folder.work / "out.ppm"), std::string("old"));
}

// Names that Windows keeps for devices (in any folder, with an extension too) and names
// with characters it does not allow are refused before the render, with nothing created:
// a rename would put the image in a device's place, or fail only once it is made.
TEST(windows_device_names_and_unusable_names_are_refused_at_once) {
    const std::string device = "is not a regular file (a device, FIFO or socket)";
    const std::string unusable = "holds a character that Windows does not allow in a file name";
    const std::pair<const char*, const std::string*> cases[] = {
        {"NUL", &device},       {"con.ppm", &device}, {"sub/aux", &device},     {"Com1.txt", &device},
        {"LPT9", &device},      {"CONOUT$", &device}, {"nul.tar.gz", &device},  {"a<b.ppm", &unusable},
        {"a?b.ppm", &unusable}, {"a|b", &unusable},   {"out.ppm:s", &unusable}, {"a\x01z.ppm", &unusable},
    };
    for (const auto& [output, why] : cases) {
        const Scratch folder;
        fs::create_directory(folder.work / "sub");
        write_bytes(folder.work / "scene.txt", small_scene(output));
        const run_program::Result r = run(folder.work, folder.root, {"scene.txt"});
        CHECK_EQ(r.status, 3);
        CHECK(r.err.find(*why) != std::string::npos);
        CHECK_EQ(folder.names(), std::string("scene.txt sub"));
    }
}

// -o may name a device: NUL takes the image, as /dev/null does elsewhere, also by its
// name in the device namespace; and a path in the \\?\ namespace is a file like any.
TEST(dash_o_writes_into_devices_and_takes_raw_paths) {
    const Scratch folder;
    write_bytes(folder.work / "scene.txt", small_scene("out.ppm"));
    for (const char* device : {"NUL", "\\\\.\\NUL"}) {
        const run_program::Result r = run(folder.work, folder.root, {"-o", device, "scene.txt"});
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err, std::string());
        CHECK_EQ(folder.names(), std::string("scene.txt"));
    }
    const std::string raw = "\\\\?\\" + fs::absolute(folder.work / "raw.ppm").string();
    const run_program::Result r = run(folder.work, folder.root, {"-o", raw, "scene.txt"});
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err, std::string());
    CHECK_EQ(folder.names(), std::string("raw.ppm scene.txt"));
}

// A folder on the way that is a link out of the working folder (a symbolic link or a
// junction) is outside it: the folder as the system opens it is compared. The links are
// made here, or under Wine by the host (folder_links.cmake).
TEST(a_folder_link_out_of_the_working_folder_is_outside_it) {
#ifdef RAYTRACER_HOST_FOLDER_LINKS
    const fs::path root = RAYTRACER_HOST_FOLDER_LINKS, work = root / "work";
#else
    const Scratch folder;
    const fs::path &root = folder.root, &work = folder.work;
    fs::create_directories(root / "elsewhere");
    fs::create_directories(work / "inside");
    // Without developer mode or the privilege, Windows refuses a symbolic link.
    if (!folder_link(root / "elsewhere", work / "escape")) {
        std::cout << "skip  folder links: this user may not make symbolic links (Windows error "
                  << GetLastError() << ")\n";
        return;
    }
    CHECK(folder_link(work / "inside", work / "alias"));
#endif
    write_bytes(work / "scene.txt", small_scene("escape/out.ppm"));
    run_program::Result r = run(work, root, {"scene.txt"});
    CHECK_EQ(r.status, 3);
    CHECK(r.err.find("OUTPUT 'escape/out.ppm' leaves the working folder through a symbolic link") !=
          std::string::npos);
    CHECK(fs::is_empty(root / "elsewhere"));
    r = run(work, root, {"scene.txt", "-o", "escape/out.ppm"});
    CHECK_EQ(r.status, 0);  // the user may
    CHECK(fs::exists(root / "elsewhere" / "out.ppm"));
    write_bytes(work / "scene.txt", small_scene("alias/out.ppm"));  // a link that stays inside
    r = run(work, root, {"scene.txt"});
    CHECK_EQ(r.status, 0);
    CHECK(fs::exists(work / "inside" / "out.ppm"));
}
