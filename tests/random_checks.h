// Shared by the randomised tests: uniform numbers from a seeded generator, a random
// scene in a mirror room, and intersect()'s answer for a shadow ray, which the culling
// tests hold each shortcut to.
#pragma once

#include <random>
#include <vector>

#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/scene.h"
#include "raytracer/vec3.h"

// Uniform in [lo, hi) from the raw generator output: the same numbers on every
// platform (std::uniform_real_distribution is not specified bit for bit).
inline double uniform(std::mt19937& g, double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(g()) / 4294967296.0);
}

// Whether ellipsoid e blocks the shadow ray from point to the light at point + to_light:
// blocks_segment(), as the unculled renderer decides.
inline bool blocks(const rt::Ellipsoid<double>& e, const rt::Vec3<double>& point,
                   const rt::Vec3<double>& to_light) {
    return rt::blocks_segment(e, point, to_light);
}

// least to least + spread - 1 random ellipsoids in front of the camera: the first a room
// (around the others and the lights the culling tests place), every third negated in y,
// some paper-thin.
inline std::vector<rt::Ellipsoid<double>> random_room_scene(std::mt19937& g, unsigned least = 3,
                                                            unsigned spread = 14) {
    std::vector<rt::Ellipsoid<double>> ellipsoids;
    const int n = static_cast<int>(least + g() % spread);
    for (int i = 0; i < n; ++i) {
        rt::SphereSpec s{};
        s.centre = {uniform(g, -5, 5), uniform(g, -5, 5), uniform(g, -10, 0)};
        s.scale = {uniform(g, 0.1, 2), uniform(g, 0.1, 2), uniform(g, 0.1, 2)};
        if (i % 3 == 1) s.scale.y = -s.scale.y;
        if (i % 7 == 3) s.scale.z = 0.001;
        if (i == 0) s.centre = {0, 0, -5}, s.scale = {14, 10, 16};  // a room
        ellipsoids.push_back(rt::make_ellipsoid<double>(s));
    }
    return ellipsoids;
}
