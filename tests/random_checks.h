// Shared by the randomised tests: uniform numbers from a seeded generator, and
// intersect()'s answer for a shadow ray, which the culling tests hold each shortcut to.
#pragma once

#include <random>

#include "raytracer/ellipsoid.h"
#include "raytracer/vec3.h"

// Uniform in [lo, hi) from the raw generator output: the same numbers on every
// platform (std::uniform_real_distribution is not specified bit for bit).
inline double uniform(std::mt19937& g, double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(g()) / 4294967296.0);
}

// Whether ellipsoid e blocks the shadow ray from point to the light at point + to_light:
// a root of intersect() in (0.001, 1), as the unculled renderer decides.
inline bool blocks(const rt::Ellipsoid<double>& e, const rt::Vec3<double>& point,
                   const rt::Vec3<double>& to_light) {
    const rt::Roots<double> r = rt::intersect(e, point, to_light);
    return r.hit && ((r.near > 0.001 && r.near < 1) || (r.far > 0.001 && r.far < 1));
}
