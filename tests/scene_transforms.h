// Transformations of a whole scene that should not change its image, or change it in a
// known way: the relations the metamorphic tests (tests/metamorphic.cpp) check.
#pragma once

#include <algorithm>
#include <cmath>

#include "raytracer/image.h"
#include "raytracer/scene.h"
#include "raytracer/scene_scale.h"

namespace transforms {

// Every length multiplied by k: positions, scales, NEAR, LEFT, RIGHT, BOTTOM, TOP and
// the lights. Every ray parameter t stays the same, so the image should too.
inline rt::Scene scaled(rt::Scene scene, double k) {
    rt::for_each_length(scene, [k](double& x) { x *= k; });
    return scene;
}

// x negated everywhere; the window [LEFT, RIGHT] becomes [-RIGHT, -LEFT].
inline rt::Scene mirrored_in_x(rt::Scene scene) {
    const double left = scene.left;
    scene.left = -scene.right;
    scene.right = -left;
    for (rt::SphereSpec& s : scene.spheres) s.centre.x = -s.centre.x;
    for (rt::LightSpec& l : scene.lights) l.position.x = -l.position.x;
    return scene;
}

// The SPHERE lines in the reverse order.
inline rt::Scene spheres_reversed(rt::Scene scene) {
    std::reverse(scene.spheres.begin(), scene.spheres.end());
    return scene;
}

// Every scale replaced by its absolute value: the unit sphere is symmetric, so the
// sign of a scale cannot matter.
inline rt::Scene scales_made_positive(rt::Scene scene) {
    for (rt::SphereSpec& s : scene.spheres)
        s.scale = {std::fabs(s.scale.x), std::fabs(s.scale.y), std::fabs(s.scale.z)};
    return scene;
}

// Pixel (c, r) shoots through the top-left corner x = LEFT + (RIGHT-LEFT) c / cols, so
// in the mirrored scene column c sees what column cols - c saw: column 0 of the mirror
// looks at x = RIGHT, which the original image does not contain. This returns the
// mirror image aligned that way, with column 0 copied from the other image so that
// only columns 1..cols-1 are compared.
inline rt::Image mirror_columns(const rt::Image& image, const rt::Image& column0_from) {
    rt::Image out = image;
    const auto w = static_cast<std::size_t>(image.width);
    for (std::size_t r = 0; r < static_cast<std::size_t>(image.height); ++r) {
        for (std::size_t c = 0; c < w; ++c) {
            const std::size_t to = (r * w + c) * 3;
            const std::size_t from = c == 0 ? to : (r * w + (w - c)) * 3;
            const rt::Image& source = c == 0 ? column0_from : image;
            for (int k = 0; k < 3; ++k) out.rgb[to + k] = source.rgb[from + k];
        }
    }
    return out;
}

}  // namespace transforms
