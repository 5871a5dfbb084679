// Every scene of scenes/ parses, renders at its own size, shows something besides the
// background, and renders the same bytes twice.
#include <filesystem>
#include <string>

#include "check.h"
#include "raytracer/parser.h"
#include "raytracer/render.h"

#ifndef RAYTRACER_SCENES_DIR
#error "RAYTRACER_SCENES_DIR must name the scenes/ folder"
#endif

namespace fs = std::filesystem;

TEST(every_scene_renders) {
    int scenes = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(RAYTRACER_SCENES_DIR)) {
        if (entry.path().extension() != ".txt") continue;
        ++scenes;
        const std::string name = entry.path().filename().string();
        const rt::Scene scene = rt::load_scene(entry.path().string());
        const rt::Image image = rt::render<double>(scene);
        CHECK_EQ(image.width, scene.columns);
        CHECK_EQ(image.height, scene.rows);
        CHECK_EQ(image.rgb.size(), static_cast<std::size_t>(scene.columns) * scene.rows * 3);
        const std::uint8_t back[3] = {rt::to_byte(scene.background.x), rt::to_byte(scene.background.y),
                                      rt::to_byte(scene.background.z)};
        long long not_background = 0;
        for (std::size_t i = 0; i < image.rgb.size(); i += 3)
            if (image.rgb[i] != back[0] || image.rgb[i + 1] != back[1] || image.rgb[i + 2] != back[2])
                ++not_background;
        const long long pixels = static_cast<long long>(scene.columns) * scene.rows;
        if (!(not_background * 10 > pixels)) std::cerr << name << ": mostly background\n";
        CHECK(not_background * 10 > pixels);  // at least 10% of the image
        const bool same = rt::render<double>(scene).rgb == image.rgb;
        if (!same) std::cerr << name << ": two renders differ\n";
        CHECK(same);
    }
    CHECK(scenes >= 4);
}
