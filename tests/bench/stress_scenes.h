// Scenes for the speed tests: the course scenes (when present) and the heavy benchmark
// scene at a given size, and random scenes built to stress the margins of the shortcuts
// (thin, far, negative-scaled and overlapping ellipsoids, lights inside them or on
// their surface, the eye inside one).
#pragma once

#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "random_checks.h"
#include "raytracer/parser.h"
#include "raytracer/scene.h"

#ifndef RAYTRACER_COURSE_SCENES
#error "RAYTRACER_COURSE_SCENES must name the course's scenes folder"
#endif
#ifndef RAYTRACER_BENCH_DIR
#error "RAYTRACER_BENCH_DIR must name tests/bench"
#endif

namespace stress {

namespace fs = std::filesystem;

inline std::vector<std::pair<std::string, rt::Scene>> file_scenes(int columns, int rows) {
    std::vector<fs::path> files;
    if (fs::is_directory(RAYTRACER_COURSE_SCENES))
        for (const fs::directory_entry& e : fs::directory_iterator(RAYTRACER_COURSE_SCENES))
            if (e.path().extension() == ".txt") files.push_back(e.path());
    files.push_back(fs::path(RAYTRACER_BENCH_DIR) / "heavy.txt");
    std::vector<std::pair<std::string, rt::Scene>> scenes;
    for (const fs::path& f : files) {
        rt::Scene s = rt::load_scene(f.string());
        s.columns = columns, s.rows = rows;  // small, odd sizes: quick, and no even split
        scenes.emplace_back(f.filename().string(), s);
    }
    return scenes;
}

inline rt::Scene random_scene(unsigned seed) {
    std::mt19937 g(seed);
    rt::Scene s;
    s.near_plane = uniform(g, 0.5, 2);
    s.left = -1, s.right = uniform(g, 0.5, 1.5), s.bottom = -1, s.top = uniform(g, 0.5, 1.5);
    s.columns = 61, s.rows = 47;
    s.background = {0.2, 0.3, 0.4};
    s.ambient = {0.3, 0.3, 0.3};
    const int spheres = 3 + static_cast<int>(g() % 10);
    for (int i = 0; i < spheres; ++i) {
        rt::SphereSpec e;
        e.centre = {uniform(g, -4, 4), uniform(g, -4, 4), uniform(g, -12, 1)};
        e.scale = {uniform(g, 0.05, 3), uniform(g, 0.05, 3), uniform(g, 0.05, 3)};
        if (g() % 4 == 0) e.scale.y = -e.scale.y;      // negated scales are legal
        if (g() % 6 == 0) e.scale.z = 0.001;           // a thin disc
        if (g() % 8 == 0) e.centre.z = -s.near_plane;  // cut by the near plane
        e.colour = {uniform(g, 0, 1), uniform(g, 0, 1), uniform(g, 0, 1)};
        e.ka = 0.2, e.kr = g() % 2 ? 0.5 : 0;
        e.kd = g() % 4 ? 0.6 : 0;  // Kd = 0 and Ks = 0 take shading shortcuts
        e.ks = g() % 3 ? 0.5 : 0;
        e.shininess = static_cast<double>(1 + g() % 60) + (g() % 2 ? 0.5 : 0);
        s.spheres.push_back(e);
    }
    if (g() % 2) {  // the eye inside a mirror room
        rt::SphereSpec room;
        room.centre = {0, 0, -4}, room.scale = {10, 8, 12}, room.colour = {0.5, 0.5, 0.5};
        room.ka = 0.1, room.kd = 0.3, room.ks = 0.2, room.kr = 0.7, room.shininess = 20;
        s.spheres.push_back(room);
    }
    const int lights = 1 + static_cast<int>(g() % 5);
    for (int i = 0; i < lights; ++i) {
        rt::LightSpec l;
        l.intensity = {0.5, 0.5, 0.5};
        l.position = {uniform(g, -6, 6), uniform(g, -6, 6), uniform(g, -12, 2)};
        const rt::SphereSpec& e = s.spheres[g() % s.spheres.size()];
        if (g() % 3 == 0) l.position = e.centre;  // a light inside an ellipsoid
        if (g() % 4 == 0)                         // a light on an ellipsoid's surface
            l.position = {e.centre.x + e.scale.x, e.centre.y, e.centre.z};
        s.lights.push_back(l);
    }
    return s;
}

}  // namespace stress
