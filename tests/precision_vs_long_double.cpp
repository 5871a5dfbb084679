// precision_vs_long_double [--real float|double] [--max-percent P] [--list] [--near-one] SCENE...
//
// Renders each scene (with --near-one, its lengths first brought near 1 as raytracer.exe
// does: scene_scale.h) in the given precision (double unless told) and in long double,
// the ground truth of the hard cases (scenes/hard/README.md), and fails when the two
// differ in more than P percent of the pixels (0.01 unless told: issue 4, item 5).
// Prints one row per scene: pixels differing, largest difference in levels, PSNR.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "precision.h"
#include "raytracer/parser.h"
#include "raytracer/scene_scale.h"

int main(int argc, char** argv) {
    precision::Real real = precision::Real::kDouble;
    double max_percent = 0.01;
    bool list = false;      // --list prints each differing pixel
    bool near_one = false;  // --near-one: as raytracer.exe renders it
    int scenes = 0, failed = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--real" && i + 1 < argc) {
            const std::string value = argv[++i];
            real = value == "float" ? precision::Real::kFloat : precision::Real::kDouble;
            continue;
        }
        if (arg == "--list") {
            list = true;
            continue;
        }
        if (arg == "--near-one") {
            near_one = true;
            continue;
        }
        if (arg == "--max-percent" && i + 1 < argc) {
            max_percent = std::atof(argv[++i]);
            continue;
        }
        ++scenes;
        try {
            rt::Scene scene = rt::load_scene(arg);
            if (near_one) rt::bring_lengths_near_one(scene);
            const rt::Image image = precision::render(scene, real);
            const rt::Image truth = precision::render(scene, precision::Real::kLongDouble);
            const precision::Error e = precision::error_of(image, truth);
            const bool ok = precision::differing_percent(e) <= max_percent;
            if (!ok) ++failed;
            std::printf(
                "%-50s %s vs long double: %lld of %lld pixels differ (%.4f%%), largest %d, PSNR %.1f dB: "
                "%s\n",
                arg.c_str(), precision::name_of(real), e.differing_pixels, e.pixels,
                precision::differing_percent(e), e.largest_difference, e.psnr, ok ? "ok" : "FAIL");
            for (std::size_t i = 0; list && i < truth.rgb.size() && i < image.rgb.size(); i += 3) {
                if (image.rgb[i] == truth.rgb[i] && image.rgb[i + 1] == truth.rgb[i + 1] &&
                    image.rgb[i + 2] == truth.rgb[i + 2])
                    continue;
                const std::size_t pixel = i / 3;
                std::printf("  (%zu,%zu): %d %d %d, long double %d %d %d\n", pixel % std::size_t(truth.width),
                            pixel / std::size_t(truth.width), image.rgb[i], image.rgb[i + 1],
                            image.rgb[i + 2], truth.rgb[i], truth.rgb[i + 1], truth.rgb[i + 2]);
            }
        } catch (const std::exception& ex) {
            ++failed;
            std::printf("%s: %s\n", arg.c_str(), ex.what());
        }
    }
    if (scenes == 0) {
        std::fprintf(
            stderr,
            "usage: precision_vs_long_double [--real float|double] [--max-percent P] [--list] [--near-one] "
            "SCENE...\n");
        return 2;
    }
    return failed == 0 ? 0 : 1;
}
