// Writes a scale scene (scale_scenes.h) as a scene file:
//
//   make_scene flake LEVEL FILE [COLUMNS ROWS]    a sphereflake, levels 1-6
//   make_scene random N FILE [COLUMNS ROWS]       N random ellipsoids (seed 1)
// RES is 400 400 unless given; OUTPUT is FILE's name with .ppm for .txt.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>

#include "scale_scenes.h"

namespace {

int make_scene(int argc, char** argv) {
    if ((argc != 4 && argc != 6) ||
        (std::strcmp(argv[1], "flake") != 0 && std::strcmp(argv[1], "random") != 0)) {
        std::fprintf(stderr,
                     "usage: make_scene flake LEVEL FILE [COLUMNS ROWS] | make_scene random N FILE [...]\n");
        return 2;
    }
    const long n = std::strtol(argv[2], nullptr, 10);
    const bool flake = std::strcmp(argv[1], "flake") == 0;
    if (flake ? (n < 1 || n > 6) : (n < 1 || n > 10000000)) {
        std::fprintf(stderr, "make_scene: %s is out of range\n", argv[2]);
        return 2;
    }
    rt::Scene scene =
        flake ? scale::sphereflake(static_cast<int>(n)) : scale::random_ellipsoids(static_cast<int>(n));
    if (argc == 6) {
        scene.columns = std::atoi(argv[4]), scene.rows = std::atoi(argv[5]);
        if (scene.columns < 1 || scene.rows < 1) {
            std::fprintf(stderr, "make_scene: the image size must be positive\n");
            return 2;
        }
    }
    const std::string file = argv[3];
    const std::size_t dot = file.rfind('.');
    scene.output =
        std::filesystem::path(file.substr(0, dot == std::string::npos ? file.size() : dot) + ".ppm")
            .filename()
            .string();
    const std::string text = scale::scene_text(scene);
    std::FILE* f = std::fopen(argv[3], "wb");
    if (f == nullptr || std::fwrite(text.data(), 1, text.size(), f) != text.size() || std::fclose(f) != 0) {
        std::fprintf(stderr, "make_scene: cannot write %s\n", argv[3]);
        return 3;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return make_scene(argc, argv);
    } catch (const std::exception& e) {  // out of memory for the scene or its text
        std::fprintf(stderr, "make_scene: %s\n", e.what());
        return 1;
    }
}
