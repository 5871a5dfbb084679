// What the tests that run raytracer.exe as a child process share (cli.cpp, faults.cpp,
// faults_windows.cpp): a fresh working folder, its files' bytes, and scenes that render
// at once or for seconds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include "raytracer/compiler.h"

namespace process_scratch {

namespace fs = std::filesystem;

// A fresh, empty working folder per test, inside a root of its own that also holds the
// captured output; both removed afterwards.
struct Scratch {
    fs::path root, work;
    Scratch() {
        std::random_device random;
        root = fs::temp_directory_path() / ("raytracer-tests-" + std::to_string(random()));
        work = root / "work";
        fs::create_directories(work);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    ~Scratch() {
        std::error_code ignored;
        fs::remove_all(root, ignored);
    }
    // The names in the working folder, sorted, separated by spaces.
    std::string names() const {
        std::vector<std::string> all;
        for (const fs::directory_entry& e : fs::directory_iterator(work))
            all.push_back(e.path().filename().string());
        std::sort(all.begin(), all.end());
        std::string joined;
        for (const std::string& name : all) joined += (joined.empty() ? "" : " ") + name;
        return joined;
    }
};

inline std::string read_bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const fs::path& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary) << bytes;
}

inline std::string small_scene(const std::string& output) {
    return "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES 100 100\nSPHERE s 0 0 -5 1 1 1 1 0 0 0.2 0.5 0.5 "
           "0.2 "
           "10\nLIGHT l 5 5 0 1 1 1\nBACK 0.5 0.25 1\nAMBIENT 0.2 0.2 0.2\nOUTPUT " +
           output + "\n";
}

// 200 ellipsoids and 200 lights scattered by a fixed generator: at RES 1200, 1.4 s on the
// build machine's two cores, 2.7 s on one, longer under the sanitizers (at RES 400 under
// ThreadSanitizer, still seconds): the fault tests interrupt it well inside its render.
#ifdef RT_UNDER_TSAN
inline constexpr int kSlowRes = 400;
#else
inline constexpr int kSlowRes = 1200;
#endif
// The size of its image: the P6 header, then 3 bytes a pixel.
inline std::size_t slow_image_bytes() {
    const std::string side = std::to_string(kSlowRes);
    return ("P6\n" + side + " " + side + "\n255\n").size() + std::size_t{3} * kSlowRes * kSlowRes;
}
inline std::string slow_scene(const std::string& output, int res = kSlowRes) {
    std::minstd_rand random(12345);
    auto u = [&random](double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(random()) / static_cast<double>(std::minstd_rand::max());
    };
    std::string text = "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES " + std::to_string(res) + " " +
                       std::to_string(res) + "\nBACK 0.1 0.1 0.1\nAMBIENT 0.2 0.2 0.2\nOUTPUT " + output +
                       "\n";
    for (int i = 0; i < 200; ++i)
        text += "SPHERE s" + std::to_string(i) + " " + std::to_string(u(-4, 4)) + " " +
                std::to_string(u(-4, 4)) + " " + std::to_string(u(-12, -5)) +
                " 0.3 0.3 0.3 0.5 0.5 0.5 0.2 0.5 0.5 0.5 10\n";
    for (int i = 0; i < 200; ++i)
        text += "LIGHT l" + std::to_string(i) + " " + std::to_string(u(-9, 9)) + " " +
                std::to_string(u(-9, 9)) + " " + std::to_string(u(-3, 3)) + " 0.01 0.01 0.01\n";
    return text;
}

}  // namespace process_scratch
