// A fake "student" renderer for the grader's tests, one executable per FAKE_MODE: it reads
// the scene's OUTPUT and the scene's key (../keys beside the scene folder) and writes the
// key with one kind of mistake, or misbehaves as a broken program does. Standard library
// only, and not built with the sanitizers: a sanitizer would turn the crash into its own
// report and exit status.
//
//   black       a black image of the key's size          one_level   every channel one level off
//   pixel64     the key with one pixel off by 64          hang        never ends
//   segfault    dies by a segmentation fault              exit1       a line on stderr, status 1
//   wrong_size  the key's top-left half in each direction wrong_name  the image as a.ppm
//   p3          the key as a text (P3) PPM                shifted     the key moved one pixel right
//   huge_header only a header of 30000x30000 pixels        escapes     terminal escapes on stderr, status 3
//   lax_header  the key under "600abc 600junk", which a PPM reader refuses
//   straggler   the key, leaving a process running (POSIX; its pid to FAKE_RENDERER_PID_FILE)
//   trailing    the key with 5 bytes after its pixels
//   dozen_steps the key with 12 pixels one level off, the most the rule allows
//   ambiguous_sides  the key with keyShadow's ambiguous (400, 150) showing its other
//               outcome, and (375, 200) showing neither
//   sparse_tail the key with 64 GiB after its pixels (sparse: no disk; POSIX tests only)
//   endless_comment  "P6\n#" and a comment of 64 GiB (sparse; POSIX tests only)
//   waits_for_enter  the key, then reads standard input to its end
//   endless_stderr   (POSIX) 64 GiB of stderr without a newline (sparse), status 1
//   fifo_output      (POSIX) a FIFO at the output's name
//   link_to_key      (POSIX) a symbolic link to the key at the output's name, no image
//   stdout_null      (POSIX) the key where standard output is the null device (nothing
//                    of it is read), status 9 where it is anything else
//   readonly_folder  (POSIX) the key, and a write-protected folder with a file in it
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#ifdef _WIN32
#include <windows.h>
#else
#include <sys/stat.h>
#include <unistd.h>
#endif

#ifndef FAKE_MODE
#error "FAKE_MODE must name the mistake"
#endif

namespace {

// Bytes that a sparse file holds without disk: more than a grader could read in its
// tests' time limit (about 2.5 s a GB).
constexpr std::uintmax_t kSparseBytes = std::uintmax_t{64} << 30;

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
};

std::string scene_output(const std::string& scene) {
    std::ifstream in(scene);
    std::string keyword, value, line;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        if (fields >> keyword >> value && keyword == "OUTPUT") return value;
    }
    return "out.ppm";
}

Image read_key(const std::string& scene) {
    const std::size_t slash = scene.find_last_of("/\\");
    const std::string folder = scene.substr(0, slash), file = scene.substr(slash + 1);
    const std::string key = folder + "/../keys/key" + file.substr(4, file.size() - 8) + ".ppm";
    std::ifstream in(key, std::ios::binary);
    std::string magic;
    int maxval = 0;
    Image image;
    in >> magic >> image.width >> image.height >> maxval;
    in.get();
    image.rgb.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
    in.read(reinterpret_cast<char*>(image.rgb.data()), static_cast<std::streamsize>(image.rgb.size()));
    if (!in) {
        std::cerr << "fake: cannot read the key " << key << "\n";
        std::exit(9);
    }
    return image;
}

void write_p6(const std::string& name, const Image& image) {
    std::ofstream out(name, std::ios::binary);
    out << "P6\n" << image.width << " " << image.height << "\n255\n";
    out.write(reinterpret_cast<const char*>(image.rgb.data()),
              static_cast<std::streamsize>(image.rgb.size()));
}

void write_p3(const std::string& name, const Image& image) {
    std::ofstream out(name);
    out << "P3\n" << image.width << " " << image.height << "\n255\n";
    for (const std::uint8_t v : image.rgb) out << int{v} << "\n";
}

Image top_left_half(const Image& image) {
    Image half;
    half.width = image.width / 2;
    half.height = image.height / 2;
    for (int y = 0; y < half.height; ++y)
        for (int x = 0; x < 3 * half.width; ++x)
            half.rgb.push_back(image.rgb[static_cast<std::size_t>(y) * 3 * image.width + x]);
    return half;
}

unsigned long process_id() {
#ifdef _WIN32
    return GetCurrentProcessId();
#else
    return static_cast<unsigned long>(getpid());
#endif
}

// Each row moved one pixel to the right (its first pixel repeated): every edge is off.
Image shifted_right(const Image& image) {
    Image moved = image;
    const std::size_t row = 3 * static_cast<std::size_t>(image.width);
    for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y)
        for (std::size_t i = 3; i < row; ++i) moved.rgb[y * row + i] = image.rgb[y * row + i - 3];
    return moved;
}

#ifdef _WIN32
// Ends the process with the exception's code, as Windows does without a debugger: Wine
// would otherwise start winedbg on the crash (it ignores SEM_NOGPFAULTERRORBOX).
LONG WINAPI end_with_exception_code(EXCEPTION_POINTERS* /*exception*/) { return EXCEPTION_EXECUTE_HANDLER; }
#endif

[[noreturn]] void crash() {
#ifdef _WIN32
    SetErrorMode(SEM_NOGPFAULTERRORBOX);
    SetUnhandledExceptionFilter(end_with_exception_code);
#endif
    volatile int* volatile nowhere = nullptr;
    *nowhere = 1;  // NOLINT(clang-analyzer-core.NullDereference): the crash is the point
    std::abort();  // not reached
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = FAKE_MODE;
    if (argc != 2) return 2;
    if (mode == "hang") {
        if (const char* pid_file = std::getenv("FAKE_RENDERER_PID_FILE"))
            std::ofstream(pid_file) << process_id() << "\n";
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    if (mode == "segfault") crash();
#ifndef _WIN32
    if (mode == "endless_stderr") {
        if (ftruncate(2, static_cast<off_t>(kSparseBytes)) != 0) return 8;
        return 1;
    }
    if (mode == "fifo_output") return mkfifo(scene_output(argv[1]).c_str(), 0644) == 0 ? 0 : 8;
    if (mode == "stdout_null") {
        struct stat out {
        }, null{};
        if (fstat(1, &out) != 0 || stat("/dev/null", &null) != 0 || out.st_dev != null.st_dev ||
            out.st_ino != null.st_ino || out.st_rdev != null.st_rdev)
            return 9;
    }
    if (mode == "link_to_key") {
        const std::string scene = std::filesystem::absolute(argv[1]).string();
        const std::string file = scene.substr(scene.find_last_of('/') + 1);
        const std::string key = scene.substr(0, scene.find_last_of('/')) + "/../keys/key" +
                                file.substr(4, file.size() - 8) + ".ppm";
        return symlink(key.c_str(), scene_output(argv[1]).c_str()) == 0 ? 0 : 8;
    }
#endif
    if (mode == "exit1") {
        std::cerr << "fake: error: cannot open the scene file\nsecond line\n";
        return 1;
    }
    if (mode == "escapes") {
        std::cerr << "\x1b[31mred\x1b[0m \a\n";
        return 3;
    }
    const std::string output = scene_output(argv[1]);
    if (mode == "huge_header") {
        std::ofstream(output, std::ios::binary) << "P6\n30000 30000\n255\n";
        return 0;
    }
#ifndef _WIN32
    if (mode == "straggler") {
        const char* pid_file = std::getenv("FAKE_RENDERER_PID_FILE");
        const std::string written = pid_file != nullptr ? std::string(pid_file) + ".written" : "";
        if (fork() == 0) {
            if (pid_file != nullptr) {
                std::ofstream(written) << getpid() << "\n";
                (void)std::rename(written.c_str(), pid_file);  // whole when it appears
            }
            for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
        }
        // Not done before the straggler is known: the grader kills it when this ends.
        for (int i = 0; pid_file != nullptr && i < 2000 && !std::ifstream(pid_file); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
#endif
    Image image = read_key(argv[1]);
    if (mode == "black") image.rgb.assign(image.rgb.size(), 0);
    if (mode == "pixel64") {
        std::uint8_t& red = image.rgb[3 * (static_cast<std::size_t>(image.width) * 200 + 300)];
        red = static_cast<std::uint8_t>(red >= 64 ? red - 64 : red + 64);  // pixel (300, 200)
    }
    if (mode == "one_level")
        for (std::uint8_t& v : image.rgb) v = static_cast<std::uint8_t>(v == 255 ? 254 : v + 1);
    if (mode == "ambiguous_sides") {  // keyShadow's (400, 150) and (375, 200), tangent to s1
        std::uint8_t* const other = &image.rgb[3 * (static_cast<std::size_t>(image.width) * 150 + 400)];
        other[0] = other[1] = other[2] = 255;  // the miss: its other outcome
        std::uint8_t* const third = &image.rgb[3 * (static_cast<std::size_t>(image.width) * 200 + 375)];
        third[0] = third[1] = 0, third[2] = 255;  // neither outcome
    }
    if (mode == "dozen_steps")
        for (std::size_t x = 0; x < 12; ++x) {  // row 300, columns 0-11, red
            std::uint8_t& red = image.rgb[3 * (static_cast<std::size_t>(image.width) * 300 + x)];
            red = static_cast<std::uint8_t>(red == 255 ? 254 : red + 1);
        }
    if (mode == "endless_comment") {
        std::ofstream(output, std::ios::binary) << "P6\n#";
        std::filesystem::resize_file(output, kSparseBytes);
        return 0;
    }
    if (mode == "wrong_size") image = top_left_half(image);
    if (mode == "shifted") image = shifted_right(image);
    if (mode == "lax_header") {
        std::ofstream(output, std::ios::binary) << "P6\n"
                                                << image.width << "abc " << image.height << "junk\n255\n"
                                                << std::string(image.rgb.begin(), image.rgb.end());
        return 0;
    }
    if (mode == "p3")
        write_p3(output, image);
    else
        write_p6(mode == "wrong_name" ? "a.ppm" : output, image);
    if (mode == "trailing") std::ofstream(output, std::ios::binary | std::ios::app) << "junk\n";
    if (mode == "sparse_tail")
        std::filesystem::resize_file(output, std::filesystem::file_size(output) + kSparseBytes);
    if (mode == "waits_for_enter")
        while (std::cin.get() != EOF) {
        }
#ifndef _WIN32
    if (mode == "readonly_folder") {
        std::filesystem::create_directory("sub");
        std::ofstream("sub/f") << "kept\n";
        chmod("sub", 0500);
    }
#endif
    return 0;
}
