// length_shift() (scene_scale.h) against its definition taken length by length: the
// exponents of the least size and of the greatest length, each found with frexp().
#include <algorithm>
#include <climits>
#include <cmath>
#include <random>

#include "check.h"
#include "raytracer/scene_scale.h"

namespace {

// The definition: the exponent of every length and size, one at a time.
int shift_by_definition(const rt::Scene& scene) {
    int least = INT_MAX, greatest = INT_MIN;
    auto exponent_of = [](double x) {
        int e = 0;
        (void)std::frexp(x, &e);
        return e;
    };
    rt::for_each_length(scene, [&](double x) {
        if (x != 0) greatest = std::max(greatest, exponent_of(x));
    });
    auto size = [&](double x) {
        if (x == 0 || !std::isfinite(x)) return;
        least = std::min(least, exponent_of(x)), greatest = std::max(greatest, exponent_of(x));
    };
    size(scene.near_plane), size(scene.right - scene.left), size(scene.top - scene.bottom);
    for (const rt::SphereSpec& s : scene.spheres) size(s.scale.x), size(s.scale.y), size(s.scale.z);
    if (least > greatest) return 0;
    if (least >= -rt::kLengthExponentRange && greatest <= rt::kLengthExponentRange) return 0;
    if (greatest - least > 3 * rt::kLengthExponentLimit) return 0;
    const int sum = least + greatest;
    const int centred = -(sum >= 0 ? sum / 2 : -((1 - sum) / 2));
    const int lowest = -rt::kLengthExponentLimit - least, highest = rt::kLengthExponentLimit - greatest;
    return std::min(highest, std::max(lowest, centred));
}

// A finite length of either sign, 0 now and then, its exponent within +-range.
double random_length(std::mt19937_64& random, int range) {
    std::uniform_int_distribution<int> exponent(-range, range), kind(0, 9);
    std::uniform_real_distribution<double> mantissa(0.5, 1.0);
    if (kind(random) == 0) return 0;
    const double x = std::ldexp(mantissa(random), exponent(random));
    return kind(random) < 5 ? -x : x;
}

rt::Scene random_scene(std::mt19937_64& random, int range) {
    rt::Scene scene;
    auto positive = [&] {
        const double x = std::abs(random_length(random, range));
        return x == 0 ? 1.0 : x;
    };
    scene.near_plane = positive();
    scene.left = -positive(), scene.right = positive();
    scene.bottom = -positive(), scene.top = positive();
    std::uniform_int_distribution<int> count(0, 6);
    for (int n = count(random); n > 0; --n) {
        rt::SphereSpec s{};
        s.centre = {random_length(random, range), random_length(random, range), random_length(random, range)};
        s.scale = {positive(), -positive(), positive()};
        scene.spheres.push_back(s);
    }
    for (int n = count(random); n > 0; --n) {
        rt::LightSpec l{};
        l.position = {random_length(random, range), random_length(random, range),
                      random_length(random, range)};
        scene.lights.push_back(l);
    }
    return scene;
}

}  // namespace

TEST(length_shift_is_its_definition_on_random_scenes) {
    std::mt19937_64 random(20261207);
    int shifted = 0;
    // Exponents within +-90 (no shift), +-400 and +-1000 (shifts, held ends, none).
    for (const int range : {90, 400, 1000}) {
        for (int n = 0; n < 3000; ++n) {
            const rt::Scene scene = random_scene(random, range);
            const int expected = shift_by_definition(scene);
            CHECK_EQ(rt::length_shift(scene), expected);
            shifted += expected != 0 ? 1 : 0;
        }
    }
    CHECK(shifted > 1000);  // the cases exercise the shift, not only the range
}

TEST(length_shift_centres_a_scene_far_from_one) {
    rt::Scene scene;
    scene.near_plane = 1e160, scene.left = -1e160, scene.right = 1e160, scene.bottom = -1e160,
    scene.top = 1e160;
    CHECK_EQ(rt::length_shift(scene), shift_by_definition(scene));
    CHECK(rt::length_shift(scene) < -500);
    scene.near_plane = 1, scene.left = -1, scene.right = 1, scene.bottom = -1, scene.top = 1;
    CHECK_EQ(rt::length_shift(scene), 0);
    // The window's width is a length too, one exponent above its edges here: 1.5 * 2^600.
    scene.left = -0.75 * std::ldexp(1.0, 600), scene.right = -scene.left;
    CHECK_EQ(rt::length_shift(scene), -301);
    CHECK_EQ(shift_by_definition(scene), -301);
}
