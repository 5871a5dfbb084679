// The speed work (issue 5) must not move a single byte: every image rendered with the
// shortcuts (culling, light buffers, shadow prefilter, threads) equals the image of the
// plain tracer that tests every ray against every ellipsoid, in float, double and long
// double, and is the same for any number of threads.
// Scenes: the course scenes (when present), the heavy benchmark scene, and random
// scenes built to stress the margins (thin, far, negative-scaled and overlapping
// ellipsoids, lights inside them or on their surface, the eye inside one).
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "check.h"
#include "raytracer/parser.h"
#include "raytracer/render.h"
#include "stress_scenes.h"

namespace {

using stress::file_scenes;
using stress::random_scene;

template <typename Real>
bool same_as_plain(const std::string& name, const rt::Scene& s) {
    const rt::Image plain = rt::render<Real>(s, 1, false);
    const rt::Image fast = rt::render<Real>(s, 2, true);
    const rt::ImageDiff d = rt::compare_images(fast, plain);
    if (d.differing_pixels != 0)
        std::cerr << name << " (" << sizeof(Real) << "-byte reals): " << d.differing_pixels
                  << " pixels differ from the plain tracer\n";
    return d.same_size && d.differing_pixels == 0;
}

}  // namespace

TEST(scene_files_match_the_plain_tracer) {
    for (const auto& [name, scene] : file_scenes(83, 67)) {
        CHECK(same_as_plain<float>(name, scene));
        CHECK(same_as_plain<double>(name, scene));
        CHECK(same_as_plain<long double>(name, scene));
    }
}

TEST(random_scenes_match_the_plain_tracer) {
    for (unsigned seed = 1; seed <= 40; ++seed) {
        const rt::Scene scene = random_scene(seed);
        const std::string name = "random scene " + std::to_string(seed);
        CHECK(same_as_plain<float>(name, scene));
        CHECK(same_as_plain<double>(name, scene));
        CHECK(same_as_plain<long double>(name, scene));
    }
}

TEST(any_thread_count_gives_the_same_bytes) {
    for (const auto& [name, scene] : file_scenes(97, 61)) {
        const rt::Image one = rt::render<double>(scene, 1);
        for (unsigned threads : {2U, 3U, 5U, 16U, 64U, 200U}) {
            const bool same = rt::render<double>(scene, threads).rgb == one.rgb;
            if (!same) std::cerr << name << ": " << threads << " threads differ from 1\n";
            CHECK(same);
        }
    }
}
