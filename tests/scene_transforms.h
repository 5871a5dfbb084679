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

// The SPHERE lines in the reverse order, but within each set of ellipsoids of the same
// centre and scale the materials stay in their order of the file: where such surfaces
// coincide the first listed wins the tie, so this scene should render as the original.
inline rt::Scene spheres_reversed_ties_kept(const rt::Scene& original) {
    rt::Scene scene = spheres_reversed(original);
    auto same_shape = [](const rt::SphereSpec& a, const rt::SphereSpec& b) {
        return a.centre.x == b.centre.x && a.centre.y == b.centre.y && a.centre.z == b.centre.z &&
               a.scale.x == b.scale.x && a.scale.y == b.scale.y && a.scale.z == b.scale.z;
    };
    const std::size_t n = scene.spheres.size();
    for (std::size_t i = 0; i < n; ++i) {  // the i-th of its set in the file and in `scene`
        std::size_t rank = 0;
        for (std::size_t j = 0; j < i; ++j) rank += same_shape(original.spheres[j], original.spheres[i]);
        for (std::size_t k = 0; k < n; ++k) {
            if (!same_shape(scene.spheres[k], original.spheres[i]) || rank-- != 0) continue;
            scene.spheres[k] = original.spheres[i];
            break;
        }
    }
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
