// Scenes far beyond the course's 15 ellipsoids, for the benchmark's scale table and the
// acceleration layer's tests: sphereflakes in the manner of E. Haines' Standard
// Procedural Databases "balls" (each sphere carries 9 children a third its size) over a
// huge flat ellipsoid as floor, 3 lights; and n small random ellipsoids in a box, 10
// lights. The same arguments give the same scene (std::mt19937 is specified exactly;
// the flake's directions come from the C library's sin and cos).
#pragma once

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "raytracer/scene.h"

namespace scale {

// The camera and image of both kinds of scene: 400x400, a 2 x 2 window at NEAR 1.
inline rt::Scene empty_scene(const std::string& output) {
    rt::Scene s;
    s.near_plane = 1, s.left = -1, s.right = 1, s.bottom = -1, s.top = 1;
    s.columns = 400, s.rows = 400;
    s.background = {0.1, 0.12, 0.2};
    s.ambient = {0.3, 0.3, 0.3};
    s.output = output;
    return s;
}

inline rt::SphereSpec sphere(const rt::Vec3<double>& centre, const rt::Vec3<double>& scale,
                             const rt::Colour& colour, double kr) {
    rt::SphereSpec e;
    e.centre = centre, e.scale = scale, e.colour = colour;
    e.ka = 0.2, e.kd = 0.6, e.ks = 0.4, e.kr = kr, e.shininess = 20;
    return e;
}

namespace detail {
inline rt::Vec3<double> cross(const rt::Vec3<double>& a, const rt::Vec3<double>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// A unit vector perpendicular to the unit vector a.
inline rt::Vec3<double> perpendicular(const rt::Vec3<double>& a) {
    const rt::Vec3<double> helper =
        std::abs(a.x) < 0.9 ? rt::Vec3<double>{1, 0, 0} : rt::Vec3<double>{0, 1, 0};
    return normalize(cross(a, helper));
}

// The 9 children of the sphere (centre, radius) whose parent lies in direction -axis:
// 6 around its equator and 3 above, each a third its size and touching it (SPD balls).
inline void add_children(rt::Scene& s, const rt::Vec3<double>& centre, double radius,
                         const rt::Vec3<double>& axis, int levels) {
    if (levels == 0) return;
    const rt::Vec3<double> u = perpendicular(axis), v = cross(axis, u);
    const double child = radius / 3, distance = radius + child;
    const double kPi = 3.14159265358979323846;
    for (int k = 0; k < 9; ++k) {
        const bool upper = k >= 6;
        const double azimuth = upper ? (2 * kPi * (k - 6) / 3 + kPi / 6) : (2 * kPi * k / 6);
        const double elevation = upper ? kPi / 3.2 : 0.0;
        const rt::Vec3<double> d = u * (std::cos(azimuth) * std::cos(elevation)) +
                                   v * (std::sin(azimuth) * std::cos(elevation)) + axis * std::sin(elevation);
        const rt::Vec3<double> c = centre + d * distance;
        s.spheres.push_back(sphere(c, {child, child, child}, {0.7, 0.6, 0.5}, 0.3));
        add_children(s, c, child, d, levels - 1);
    }
}
}  // namespace detail

// A sphereflake of the given depth (level 3: 821 ellipsoids with the floor; 4: 7,382;
// 5: 66,431).
inline rt::Scene sphereflake(int level) {
    rt::Scene s = empty_scene("flake" + std::to_string(level) + ".ppm");
    const rt::Vec3<double> centre{0, 0, -4.2};
    s.spheres.push_back(sphere({0, -1.6, -4}, {40, 0.05, 40}, {0.5, 0.5, 0.45}, 0.1));
    s.spheres.push_back(sphere(centre, {1, 1, 1}, {0.7, 0.6, 0.5}, 0.3));
    detail::add_children(s, centre, 1, {0, 1, 0}, level);
    const double positions[3][3] = {{-4, 5, 2}, {5, 3, 0}, {0, 6, -8}};
    for (const auto& p : positions) {
        rt::LightSpec l;
        l.position = {p[0], p[1], p[2]};
        l.intensity = {0.5, 0.5, 0.5};
        s.lights.push_back(l);
    }
    return s;
}

// n ellipsoids of random centres, scales and materials in a box in front of the camera
// (a quarter of them mirrors), sized so that the box looks about as full for any n.
inline rt::Scene random_ellipsoids(int n, unsigned seed = 1) {
    rt::Scene s = empty_scene("random" + std::to_string(n) + ".ppm");
    std::mt19937 g(seed);
    auto uniform = [&](double lo, double hi) {
        return lo + (hi - lo) * (static_cast<double>(g() >> 5) / static_cast<double>(1U << 27));
    };
    const double size = 0.3 * std::cbrt(2000.0 / n);
    for (int i = 0; i < n; ++i) {
        const rt::Vec3<double> c{uniform(-6, 6), uniform(-6, 6), uniform(-26, -6)};
        const rt::Vec3<double> scale{size * uniform(0.5, 1.5), size * uniform(0.5, 1.5),
                                     size * uniform(0.5, 1.5)};
        s.spheres.push_back(
            sphere(c, scale, {uniform(0.2, 1), uniform(0.2, 1), uniform(0.2, 1)}, g() % 4 == 0 ? 0.5 : 0));
    }
    for (int i = 0; i < 10; ++i) {
        rt::LightSpec l;
        l.position = {uniform(-8, 8), uniform(-8, 8), uniform(-20, 4)};
        l.intensity = {0.15, 0.15, 0.15};
        s.lights.push_back(l);
    }
    return s;
}

// random_ellipsoids(2000) with every ellipsoid flattened to a disc 10^-exponent thick
// (its y scale): thin beside the scene, so that the tree's boxes must be grown to cull
// rays from across it (BoxGaps, slab_rays.h).
inline rt::Scene random_discs(int exponent) {
    rt::Scene s = random_ellipsoids(2000);
    s.output = "discs" + std::to_string(exponent) + ".ppm";
    for (rt::SphereSpec& e : s.spheres) e.scale.y = std::pow(10.0, -exponent);
    return s;
}

// The scene as a file the parser reads back to the same numbers (%.17g round-trips).
inline std::string scene_text(const rt::Scene& s) {
    std::string text;
    char line[512];
    auto put = [&](const char* format, auto... values) {
        std::snprintf(line, sizeof line, format, values...);
        text += line;
    };
    put("NEAR %.17g\nLEFT %.17g\nRIGHT %.17g\nBOTTOM %.17g\nTOP %.17g\nRES %d %d\n", s.near_plane, s.left,
        s.right, s.bottom, s.top, s.columns, s.rows);
    int k = 0;
    for (const rt::SphereSpec& e : s.spheres)
        put("SPHERE s%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g "
            "%.17g\n",
            k++, e.centre.x, e.centre.y, e.centre.z, e.scale.x, e.scale.y, e.scale.z, e.colour.x, e.colour.y,
            e.colour.z, e.ka, e.kd, e.ks, e.kr, e.shininess);
    k = 0;
    for (const rt::LightSpec& l : s.lights)
        put("LIGHT l%d %.17g %.17g %.17g %.17g %.17g %.17g\n", k++, l.position.x, l.position.y, l.position.z,
            l.intensity.x, l.intensity.y, l.intensity.z);
    put("BACK %.17g %.17g %.17g\nAMBIENT %.17g %.17g %.17g\nOUTPUT %s\n", s.background.x, s.background.y,
        s.background.z, s.ambient.x, s.ambient.y, s.ambient.z, s.output.c_str());
    return text;
}

}  // namespace scale
