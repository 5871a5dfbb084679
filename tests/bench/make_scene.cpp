// Writes a scale scene (scale_scenes.h) as a scene file:
//
//   make_scene flake LEVEL FILE [COLUMNS ROWS]    a sphereflake, levels 1-6
//   make_scene random N FILE [COLUMNS ROWS]       N random ellipsoids (seed 1)
//   make_scene discs E FILE [COLUMNS ROWS]        2,000 of them as discs 10^-E thick
// RES is 400 400 unless given; OUTPUT is FILE's name with .ppm for .txt.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

#include "scale_scenes.h"

namespace {

int make_scene(int argc, char** argv) {
    const std::string kind = argc == 4 || argc == 6 ? argv[1] : "";
    if (kind != "flake" && kind != "random" && kind != "discs") {
        std::fprintf(stderr,
                     "usage: make_scene flake LEVEL FILE [COLUMNS ROWS] | make_scene random N FILE [...] | "
                     "make_scene discs E FILE [...]\n");
        return 2;
    }
    const long n = std::strtol(argv[2], nullptr, 10);
    const long most = kind == "flake" ? 6 : kind == "discs" ? 300 : 10000000;
    if (n < (kind == "discs" ? 0 : 1) || n > most) {
        std::fprintf(stderr, "make_scene: %s is out of range\n", argv[2]);
        return 2;
    }
    const int k = static_cast<int>(n);
    rt::Scene scene = kind == "flake"    ? scale::sphereflake(k)
                      : kind == "random" ? scale::random_ellipsoids(k)
                                         : scale::random_discs(k);
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
