// The acceleration layer (bvh.h) changes no byte:
// - every Bvh query answers as BruteForce, the definition, bit for bit, on random
//   ellipsoid sets built to stress the boxes' margins (thin, far, tiny, huge,
//   negative-scaled, coincident and touching ellipsoids; rays from the camera, from
//   surface points and towards lights, grazing ones among them);
// - the tree's path (render_whitted_to(), which render() takes past
//   takes_the_tree()) renders large scenes and every scene file as the reference
//   (render(..., accelerate = false): whitted.h with brute_force.h), in float, double
//   and long double and for any number of threads.
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/brute_force.h"
#include "raytracer/bvh.h"
#include "raytracer/parser.h"
#include "raytracer/render.h"
#include "raytracer/render_whitted.h"
#include "raytracer/whitted.h"
#include "scale_scenes.h"
#include "stress_scenes.h"

namespace {

namespace fs = std::filesystem;

// n ellipsoids mixing every case the boxes' margins must hold for.
rt::Scene hard_crowd(unsigned seed, int n) {
    std::mt19937 g(seed);
    rt::Scene s = stress::random_scene(seed);
    while (static_cast<int>(s.spheres.size()) < n) {
        rt::SphereSpec e = s.spheres[g() % s.spheres.size()];
        const unsigned kind = g() % 8;
        const double size = kind == 0 ? 1e-5 : kind == 1 ? 3 : uniform(g, 0.02, 0.6);
        e.centre = {uniform(g, -5, 5), uniform(g, -5, 5), uniform(g, -14, 1)};
        e.scale = {size * uniform(g, 0.3, 1), size * uniform(g, 0.3, 1), size * uniform(g, 0.3, 1)};
        if (kind == 2) e.scale.z = 1e-7;                    // paper-thin
        if (kind == 3) e.scale.x = -e.scale.x;              // negated
        if (kind == 4) e.centre = s.spheres.back().centre;  // coincident centres
        if (kind == 5) e.centre.z = -s.near_plane;          // cut by the near plane
        if (kind == 6)                                      // touching the previous one
            e.centre = s.spheres.back().centre + rt::Vec3<double>{s.spheres.back().scale.x + e.scale.x, 0, 0};
        s.spheres.push_back(e);
    }
    if (seed % 3 == 0) {  // far away, relative to the smallest scales
        for (rt::SphereSpec& e : s.spheres) e.centre = e.centre * 1e4, e.scale = e.scale * 1e4;
        for (rt::LightSpec& l : s.lights) l.position = l.position * 1e4;
        s.near_plane *= 1e4, s.left *= 1e4, s.right *= 1e4, s.bottom *= 1e4, s.top *= 1e4;
    }
    return s;
}

template <typename Real>
bool same_hit(const rt::NearestHit<Real>& a, const rt::NearestHit<Real>& b) {
    return a.ellipsoid == b.ellipsoid && (!a.found() || (a.t == b.t && a.inside == b.inside));
}

// Random rays of every kind against a scene's ellipsoids: both queries as BruteForce's.
template <typename Real>
int queries_differing(const rt::Scene& scene, unsigned seed) {
    using V = rt::Vec3<Real>;
    std::vector<rt::Ellipsoid<Real>> all;
    for (const rt::SphereSpec& s : scene.spheres) all.push_back(rt::make_ellipsoid<Real>(s));
    const rt::BruteForce<Real> plain(all);
    const rt::Bvh<Real> tree(all);
    std::mt19937 g(seed);
    int differing = 0;
    std::uint32_t tree_hint = rt::kNoBlocker;  // carried from ray to ray, as per light in a render
    for (int k = 0; k < 3000; ++k) {
        const rt::Ellipsoid<Real>& target = all[g() % all.size()];
        // A point on the target's surface (a hit point), the camera, or anywhere.
        const V u = normalize(V{Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1))});
        const V on_surface = target.centre + u * target.scale;
        const unsigned kind = g() % 3;
        const V origin = kind == 0 ? V{} : kind == 1 ? on_surface : V::from(scene.lights[0].position);
        // Towards another ellipsoid's centre or just past its rim (grazing), or a light.
        const rt::Ellipsoid<Real>& aim = all[g() % all.size()];
        const V rim = aim.centre + V{aim.scale.x * Real(uniform(g, 0.99, 1.01)), 0, 0};
        const V to = g() % 2 ? rim : V::from(scene.lights[g() % scene.lights.size()].position);
        const V direction = to - origin;
        for (double min_t : {1.0, 0.0001})
            differing +=
                !same_hit(tree.closest(origin, direction, min_t), plain.closest(origin, direction, min_t));
        // With and without a hint, which changes the order of the tests only.
        std::uint32_t no_hint = rt::kNoBlocker, plain_hint = rt::kNoBlocker;
        const bool blocked = plain.occluded(origin, direction, plain_hint);
        differing += tree.occluded(origin, direction, no_hint) != blocked;
        differing += tree.occluded(origin, direction, tree_hint) != blocked;
    }
    return differing;
}

// Collects the rows of render_whitted_to() into an image.
struct ImageSink final : rt::RowSink {
    rt::Image image;
    void rows(const std::uint8_t* bytes, std::size_t size) override {
        image.rgb.insert(image.rgb.end(), bytes, bytes + size);
    }
};

// The tree's path (render_whitted_to(), which render() takes past
// takes_the_tree()) against the reference.
template <typename Real>
bool renders_as_plain(const std::string& name, const rt::Scene& s, unsigned threads) {
    const rt::Image plain = rt::render<Real>(s, 1, false);
    ImageSink sink;
    sink.image.width = s.columns, sink.image.height = s.rows;
    rt::render_whitted_to<Real>(s, sink, threads);
    const rt::Image& fast = sink.image;
    const rt::ImageDiff d = rt::compare_images(fast, plain);
    if (!d.same_size || d.differing_pixels != 0)
        std::cerr << name << " (" << sizeof(Real) << "-byte reals): " << d.differing_pixels
                  << " pixels differ from the reference\n";
    return d.same_size && d.differing_pixels == 0;
}

// Every scene file of the repository and the course, at a small odd size.
std::vector<std::pair<std::string, rt::Scene>> all_scene_files() {
    std::vector<std::pair<std::string, rt::Scene>> scenes = stress::file_scenes(83, 67);
    for (const char* folder : {"scenes", "scenes/hard", "tests/degenerate"})
        for (const fs::directory_entry& e : fs::directory_iterator(fs::path(RAYTRACER_SOURCE_DIR) / folder))
            if (e.path().extension() == ".txt") {
                rt::Scene s = rt::load_scene(e.path().string());
                s.columns = std::min(s.columns, 83), s.rows = std::min(s.rows, 67);
                scenes.emplace_back(e.path().filename().string(), s);
            }
    return scenes;
}

}  // namespace

TEST(bvh_queries_match_brute_force) {
    for (unsigned seed = 1; seed <= 12; ++seed) {
        const rt::Scene scene = hard_crowd(seed, 65 + static_cast<int>(seed) * 37);
        CHECK_EQ(queries_differing<float>(scene, seed), 0);
        CHECK_EQ(queries_differing<double>(scene, seed), 0);
        CHECK_EQ(queries_differing<long double>(scene, seed), 0);
    }
}

// Many ellipsoids at one centre (the builder cannot split them by position), and more
// than a leaf holds: the median split keeps the tree within its depth.
TEST(bvh_of_coincident_ellipsoids) {
    rt::Scene scene = hard_crowd(7, 70);
    for (rt::SphereSpec& e : scene.spheres) e.centre = {0.5, -0.25, -6};
    CHECK_EQ(queries_differing<double>(scene, 7), 0);
}

TEST(scenes_render_through_the_tree_as_the_plain_tracer) {
    std::vector<std::pair<std::string, rt::Scene>> scenes;
    scenes.emplace_back("sphereflake level 2", scale::sphereflake(2));
    scenes.emplace_back("random 300", scale::random_ellipsoids(300));
    for (unsigned seed = 1; seed <= 6; ++seed)
        scenes.emplace_back("hard crowd " + std::to_string(seed), hard_crowd(seed, 120));
    for (const auto& [name, scene] : all_scene_files()) scenes.emplace_back(name, scene);
    unsigned threads = 1;
    for (auto& [name, scene] : scenes) {
        scene.columns = std::min(scene.columns, 71), scene.rows = std::min(scene.rows, 53);
        CHECK(renders_as_plain<float>(name, scene, threads));
        CHECK(renders_as_plain<double>(name, scene, threads));
        CHECK(renders_as_plain<long double>(name, scene, threads));
        threads = threads % 7 + 1;
    }
}

// render() itself takes the tree past kFlatSweepEllipsoids: the same bytes.
TEST(render_takes_the_tree_past_the_flat_sweep) {
    rt::Scene scene = scale::random_ellipsoids(static_cast<int>(rt::kFlatSweepEllipsoids) + 1);
    scene.columns = 61, scene.rows = 41;
    const rt::Image plain = rt::render<double>(scene, 1, false);
    const rt::Image fast = rt::render<double>(scene, 2, true);
    CHECK(fast.rgb == plain.rgb);
}

// And past kFlatSweepPairs ellipsoid-light pairs, with few ellipsoids but many lights.
TEST(render_takes_the_tree_past_the_flat_sweeps_pairs) {
    rt::Scene scene = scale::random_ellipsoids(100);
    while (scene.lights.size() * scene.spheres.size() <= rt::kFlatSweepPairs) {
        rt::LightSpec l = scene.lights[scene.lights.size() % 10];
        l.position.x += 0.01 * static_cast<double>(scene.lights.size());
        l.intensity = {0.002, 0.002, 0.002};
        scene.lights.push_back(l);
    }
    CHECK(rt::takes_the_tree(scene.spheres.size(), scene.lights.size()));
    CHECK(!rt::takes_the_tree(scene.spheres.size(), 10));
    scene.columns = 31, scene.rows = 23;
    CHECK(rt::render<double>(scene, 2, true).rgb == rt::render<double>(scene, 1, false).rgb);
}

// Built on two threads (past BinaryTreeBuilder::kItemsPerThread a half), the tree is
// the one built on one: as many nodes, and every query answers alike.
TEST(bvh_built_on_two_threads_is_the_same_tree) {
    const rt::Scene scene = scale::random_ellipsoids(50000);
    const std::vector<rt::Ellipsoid<double>> all = rt::make_ellipsoids<double>(scene);
    const rt::Bvh<double> one(all, 1), two(all, 2);
    CHECK_EQ(one.node_count(), two.node_count());
    std::mt19937 g(11);
    int differing = 0;
    std::uint32_t hint_one = rt::kNoBlocker, hint_two = rt::kNoBlocker;
    for (int k = 0; k < 20000; ++k) {
        const rt::Vec3<double> origin{uniform(g, -6, 6), uniform(g, -6, 6), uniform(g, -26, -6)};
        const rt::Vec3<double> direction{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)};
        differing +=
            !same_hit(one.closest(origin, direction, 0.0001), two.closest(origin, direction, 0.0001));
        differing += one.occluded(origin, direction, hint_one) != two.occluded(origin, direction, hint_two);
    }
    CHECK_EQ(differing, 0);
}
