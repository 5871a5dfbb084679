// Metamorphic tests (issue 4, item 4): relations between the images of related scenes,
// which hold without knowing the right image. Each runs over every hard case
// (scenes/hard/) and every course scene (rendered at a third of its size to stay fast),
// in double, the precision of raytracer.exe.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "check.h"
#include "precision.h"
#include "raytracer/parser.h"
#include "raytracer/scene_scale.h"
#include "scene_transforms.h"

namespace fs = std::filesystem;

namespace {

struct Case {
    std::string name;
    rt::Scene scene;
};

const std::vector<Case>& cases() {
    static const std::vector<Case> all = [] {
        std::vector<Case> found;
        for (const char* folder : {RAYTRACER_HARD_SCENES, RAYTRACER_COURSE_SCENES}) {
            std::error_code ec;
            if (!fs::is_directory(folder, ec)) continue;
            std::vector<fs::path> files;
            for (const auto& entry : fs::directory_iterator(folder))
                if (entry.path().extension() == ".txt") files.push_back(entry.path());
            std::sort(files.begin(), files.end());
            for (const fs::path& file : files) {
                rt::Scene scene = rt::load_scene(file.string());
                if (scene.columns > 200) {  // the course's 600 x 600 scenes
                    scene.columns /= 3;
                    scene.rows /= 3;
                }
                found.push_back({file.stem().string(), scene});
            }
        }
        return found;
    }();
    return all;
}

rt::Image render(const rt::Scene& scene) { return rt::render<double>(scene); }

long long differing(const rt::Image& a, const rt::Image& b) {
    return precision::error_of(a, b).differing_pixels;
}

// At most this many pixels per scene may differ where the relation holds only up to
// rounding (see the tests that use it).
long long rounding_allowance(const rt::Scene& scene) {
    return static_cast<long long>(scene.columns) * scene.rows / 10000;  // 0.01%
}

}  // namespace

TEST(there_are_enough_scenes) { CHECK(cases().size() >= 15); }

// Scaling by a power of two is exact in binary floating point, so every intermediate
// value scales exactly, every t is the same, and the image must be identical.
TEST(scaling_by_a_power_of_two_changes_no_pixel) {
    for (const Case& c : cases()) {
        const rt::Image original = render(c.scene);
        for (double k : {std::ldexp(1.0, -13), std::ldexp(1.0, 10), std::ldexp(1.0, 20)}) {
            const long long d = differing(render(transforms::scaled(c.scene, k)), original);
            if (d != 0) std::cerr << c.name << " scaled by " << k << ": " << d << " pixels differ\n";
            CHECK_EQ(d, 0);
        }
    }
}

// Scaled by 2^600 or 2^-600, a scene's squared lengths overflow or underflow; brought
// near 1 again by raytracer.exe's bring_lengths_near_one(), it renders the same bytes
// as the scene brought near 1 from its own size (where the scaled lengths stay normal
// numbers: a disc 1e-300 thin cannot be scaled down by 2^600).
TEST(a_scene_of_extreme_size_renders_as_at_its_own) {
    auto stays_normal = [](const rt::Scene& s, int shift) {
        bool normal = true;
        rt::for_each_length(s, [&](double x) {
            int e = 0;
            (void)std::frexp(x, &e);
            normal = normal && (x == 0 || (e + shift > -1020 && e + shift < 1020));
        });
        return normal;
    };
    int compared = 0;
    for (const Case& c : cases()) {
        rt::Scene own = c.scene;
        rt::bring_lengths_near_one(own);
        const rt::Image original = render(own);
        for (const int shift : {600, -600}) {
            if (!stays_normal(c.scene, shift)) continue;
            rt::Scene scaled = transforms::scaled(c.scene, std::ldexp(1.0, shift));
            rt::bring_lengths_near_one(scaled);
            const long long d = differing(render(scaled), original);
            if (d != 0) std::cerr << c.name << " scaled by 2^" << shift << ": " << d << " pixels differ\n";
            CHECK_EQ(d, 0);
            ++compared;
        }
    }
    CHECK(compared >= 30);
}

// Scaling by 1e-4, 1e3 or 1e6 rounds each scaled number, i.e. moves the scene by up to
// half an ulp: only pixels that sit within rounding of an edge or of a truncation step
// may change, and then by one level at an edge's colour. Allowed: 0.01% of the pixels.
// near_plane_ring is left out: its window frames nothing but such pixels (a ring where the
// point at t = 1 lies at the allowance's edge, exact as written and not once scaled).
TEST(scaling_by_a_power_of_ten_changes_at_most_rounding_pixels) {
    for (const Case& c : cases()) {
        if (c.name == "near_plane_ring") continue;
        const rt::Image original = render(c.scene);
        for (double k : {1e-4, 1e3, 1e6}) {
            const long long d = differing(render(transforms::scaled(c.scene, k)), original);
            if (d > 0) std::cerr << c.name << " scaled by " << k << ": " << d << " pixels differ\n";
            CHECK(d <= rounding_allowance(c.scene));
        }
    }
}

// Negating x mirrors the image (one column off: pixels are sampled at their left
// corner). The mirrored pixel positions are computed by different roundings
// (-RIGHT + w c'/cols rather than -(LEFT + w c/cols)), so rounding pixels may differ.
TEST(negating_x_mirrors_the_image) {
    for (const Case& c : cases()) {
        const rt::Image original = render(c.scene);
        const rt::Image mirrored = render(transforms::mirrored_in_x(c.scene));
        const long long d = differing(transforms::mirror_columns(mirrored, original), original);
        if (d > 0) std::cerr << c.name << " mirrored: " << d << " pixels differ\n";
        CHECK(d <= rounding_allowance(c.scene));
    }
}

// Each ellipsoid's roots are computed alone and the nearest wins, and a shadow is cast
// by any blocker: the order of the SPHERE lines cannot matter, except where two
// surfaces coincide (then the first listed wins the tie).
TEST(sphere_order_changes_nothing_unless_surfaces_coincide) {
    for (const Case& c : cases()) {
        const long long d = differing(render(transforms::spheres_reversed(c.scene)), render(c.scene));
        if (c.name == "coincident") {
            CHECK(d > 0);  // the twins' colours swap
            const long long kept =
                differing(render(transforms::spheres_reversed_ties_kept(c.scene)), render(c.scene));
            if (kept > 0) std::cerr << c.name << " reversed, ties kept: " << kept << " pixels differ\n";
            CHECK_EQ(kept, 0);
        } else {
            if (d > 0) std::cerr << c.name << " reversed: " << d << " pixels differ\n";
            CHECK_EQ(d, 0);
        }
    }
}

// Negation is exact and the unit sphere is symmetric: a negative scale renders exactly
// like its absolute value.
TEST(negative_scales_render_like_positive_ones) {
    for (const Case& c : cases()) {
        const long long d = differing(render(transforms::scales_made_positive(c.scene)), render(c.scene));
        if (d > 0) std::cerr << c.name << " with positive scales: " << d << " pixels differ\n";
        CHECK_EQ(d, 0);
    }
}
