#include "raytracer/scene_scale.h"

#include <algorithm>
#include <cmath>

namespace rt {
int length_shift(const Scene& scene) {
    // The exponents of the least size and of the greatest length: |x| in
    // [2^(e - 1), 2^e). Sizes (NEAR, the window's width and height, the scales) are
    // squared and divided by; coordinates enter only through differences, where one far
    // below the scene's size counts as 0, so they bound the top alone. The exponent
    // grows with |x|, so the extremes' exponents are those of the extreme magnitudes:
    // one frexp() each rather than nine a sphere (random 100k: 3 ms of a 65 ms
    // preparation). NaN, infinities and zeros have no exponent and are passed over.
    auto usable = [](double x) { return x != 0 && std::isfinite(x); };
    double largest = 0, least_size = 0;  // 0: none yet
    for_each_length(scene, [&](double x) {
        if (usable(x)) largest = std::max(largest, std::abs(x));
    });
    auto size = [&](double x) {  // a width may overflow: its ends count
        if (!usable(x)) return;
        largest = std::max(largest, std::abs(x));
        least_size = least_size == 0 ? std::abs(x) : std::min(least_size, std::abs(x));
    };
    size(scene.near_plane), size(scene.right - scene.left), size(scene.top - scene.bottom);
    for (const SphereSpec& s : scene.spheres) size(s.scale.x), size(s.scale.y), size(s.scale.z);
    if (least_size == 0) return 0;  // no size (a parsed scene has NEAR > 0)
    int least = 0, greatest = 0;
    (void)std::frexp(least_size, &least);
    (void)std::frexp(largest, &greatest);
    if (least >= -kLengthExponentRange && greatest <= kLengthExponentRange) return 0;
    // Held at the top, a span past three times the limit would take a size to 0.
    if (greatest - least > 3 * kLengthExponentLimit) return 0;
    // Centred, unless that takes an end past 2^+-kLengthExponentLimit, where squares
    // leave the normal numbers. Where no shift holds both ends (a span past twice the
    // limit), the greatest is held: an overflowing length costs every ray its light, an
    // underflowing size only its own ellipsoid's shading.
    const int sum = least + greatest;
    const int centred = -(sum >= 0 ? sum / 2 : -((1 - sum) / 2));  // half the sum rounded down
    const int lowest = -kLengthExponentLimit - least, highest = kLengthExponentLimit - greatest;
    return std::min(highest, std::max(lowest, centred));
}

void scale_lengths(Scene& scene, int shift) {
    for_each_length(scene, [shift](double& x) { x = std::ldexp(x, shift); });
}

}  // namespace rt
