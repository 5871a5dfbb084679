#include "raytracer/scene_scale.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace rt {
namespace {

// Calls f with every length of the scene, in place.
template <typename SceneType, typename F>
void for_each_length(SceneType& scene, F f) {
    for (auto* x : {&scene.near_plane, &scene.left, &scene.right, &scene.bottom, &scene.top}) f(*x);
    auto each = [&f](auto& v) { f(v.x), f(v.y), f(v.z); };
    for (auto& s : scene.spheres) each(s.centre), each(s.scale);
    for (auto& l : scene.lights) each(l.position);
}

}  // namespace

int length_shift(const Scene& scene) {
    int least = INT_MAX, greatest = INT_MIN;
    for_each_length(scene, [&](double x) {
        if (x == 0) return;
        int exponent = 0;
        (void)std::frexp(x, &exponent);  // |x| in [2^(exponent-1), 2^exponent)
        least = std::min(least, exponent), greatest = std::max(greatest, exponent);
    });
    if (least > greatest) return 0;  // no nonzero length (a parsed scene has NEAR > 0)
    if (least >= -kLengthExponentRange && greatest <= kLengthExponentRange) return 0;
    if (greatest - least > 2000) return 0;
    // Half the sum rounded down, not toward zero: a scene and the same scene times 2^m
    // end on the same numbers.
    const int sum = least + greatest;
    return -(sum >= 0 ? sum / 2 : -((1 - sum) / 2));
}

void scale_lengths(Scene& scene, int shift) {
    for_each_length(scene, [shift](double& x) { x = std::ldexp(x, shift); });
}

}  // namespace rt
