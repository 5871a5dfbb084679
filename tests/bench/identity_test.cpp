// The fast paths (render.cpp: the flat sweep, and the tree for what it hands on) must
// not move a single byte: every image rendered with their shortcuts (culling, light
// cones, shadow prefilter, packets, threads) equals the image of the reference
// (whitted.h with brute_force.h: every ray against every ellipsoid), in float (the
// tree), double and long double, and is the same for any number of threads.
// Scenes: the course scenes (when present), the heavy benchmark scene, and random
// scenes built to stress the margins (thin, far, negative-scaled and overlapping
// ellipsoids, lights inside them or on their surface, the eye inside one), and scenes of
// 65-200 ellipsoids.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "check.h"
#include "image_diff.h"
#include "raytracer/flat_sweep/packet_tracer.h"
#include "raytracer/flat_sweep/render_flat_sweep.h"
#include "raytracer/parser.h"
#include "raytracer/render.h"
#include "scale_scenes.h"
#include "stress_scenes.h"

namespace {

using stress::file_scenes;
using stress::random_scene;

// Records what render() hands its sink: the calls' sizes and their bytes, in order.
struct RecordingSink final : rt::RowSink {
    std::vector<std::size_t> sizes;
    rt::Bytes bytes;
    void write_rows(const std::uint8_t* data, std::size_t size) override {
        sizes.push_back(size);
        bytes.insert(bytes.end(), data, data + size);
    }
};

template <typename Real>
bool same_as_plain(const std::string& name, const rt::Scene& s) {
    const rt::Image plain = rt::render_reference<Real>(s, 1);
    const rt::Image fast = rt::render<Real>(s, 2);
    const ImageDiff d = compare_images(fast, plain);
    if (d.differing_pixels != 0)
        std::cerr << name << " (" << sizeof(Real) << "-byte reals): " << d.differing_pixels
                  << " pixels differ from the reference\n";
    return d.same_size && d.differing_pixels == 0;
}

}  // namespace

TEST(scene_files_match_the_plain_tracer) {
    for (const auto& [name, scene] : file_scenes(83, 67)) {
        CHECK(same_as_plain<float>(name, scene));
        CHECK(same_as_plain<double>(name, scene));
        CHECK(same_as_plain<long double>(name, scene));
    }
}

TEST(random_scenes_match_the_plain_tracer) {
    for (unsigned seed = 1; seed <= 40; ++seed) {
        const rt::Scene scene = random_scene(seed);
        const std::string name = "random scene " + std::to_string(seed);
        CHECK(same_as_plain<float>(name, scene));
        CHECK(same_as_plain<double>(name, scene));
        CHECK(same_as_plain<long double>(name, scene));
    }
}

// Scenes of 65 to 200 ellipsoids, which the flat sweep renders with sets of ellipsoids
// wider than a word (ellipsoid_set.h): random ones, the first of sphereflake 3
// (mirrors), and a crowd in a mirror room (the last ellipsoid) around the eye and the
// lights, with a light inside ellipsoid 100 (the rules for enclosures past the first
// word).
TEST(scenes_of_many_ellipsoids_match_the_plain_tracer) {
    std::vector<std::pair<std::string, rt::Scene>> scenes;
    for (const int n : {65, 130, 200})
        scenes.emplace_back("random " + std::to_string(n), scale::random_ellipsoids(n, 7));
    rt::Scene flake = scale::sphereflake(3);
    flake.spheres.resize(150);
    scenes.emplace_back("the first 150 of sphereflake 3", flake);
    rt::Scene room = scale::random_ellipsoids(129, 11);
    room.spheres.push_back(scale::sphere({0, 0, -10}, {30, 30, 30}, {0.5, 0.5, 0.5}, 0.5));
    room.lights[0].position = room.spheres[100].centre;
    scenes.emplace_back("a crowd of 129 in a mirror room", room);
    for (auto& [name, scene] : scenes) {
        // As many pixels as pairs of ellipsoids, the least the flat sweep takes.
        scene.columns = scene.rows = static_cast<int>(scene.spheres.size());
        CHECK(!rt::takes_the_tree(scene));
        CHECK(rt::PacketTracer<double>(scene).can_render());
        CHECK(same_as_plain<double>(name, scene));
        CHECK(same_as_plain<long double>(name, scene));
    }
}

// A disc so thin that rounding could reach the bounding spheres' gap: the flat sweep
// renders it without its culling tables among at most kUnculledEllipsoids, and hands
// more to the tree. An image of fewer pixels than pairs of ellipsoids: the flat sweep
// hands it to the tree (PacketTracer::can_render()).
TEST(scenes_past_the_flat_sweeps_tables_match_the_plain_tracer) {
    rt::Scene thin = random_scene(3);
    thin.spheres[0].scale.z = 1e-9;
    rt::Scene thin_few = thin;
    thin_few.spheres.resize(rt::PacketTracer<double>::kUnculledEllipsoids);
    rt::Scene tiny = scale::random_ellipsoids(100, 7);
    tiny.columns = 9, tiny.rows = 9;
    CHECK(thin.spheres.size() > rt::PacketTracer<double>::kUnculledEllipsoids);
    CHECK(rt::PacketTracer<double>(thin_few).can_render());
    CHECK(!rt::PacketTracer<double>(thin).can_render());
    CHECK(!rt::PacketTracer<double>(tiny).can_render());
    for (const rt::Scene& scene : {thin_few, thin, tiny}) {
        CHECK(!rt::takes_the_tree(scene));
        CHECK(same_as_plain<double>("past the tables", scene));
        CHECK(same_as_plain<long double>("past the tables", scene));
    }
}

// render_to() hands its sink the whole image, in order, in whole rows, and (at 400
// columns, on one thread) in more than one call: the rows are written while later ones
// render.
TEST(the_sink_gets_every_row_in_order) {
    for (const auto& [name, scene] : file_scenes(400, 121)) {
        const rt::Image image = rt::render_reference<double>(scene, 1);
        for (unsigned threads : {1U, 2U, 3U, 8U}) {
            RecordingSink sink;
            rt::render_to<double>(scene, sink, threads);
            CHECK(sink.bytes == image.rgb);
            const std::size_t row = std::size_t{400} * 3;
            for (std::size_t size : sink.sizes) CHECK(size > 0 && size % row == 0);
            // One thread finishes rows in order: a block is out before the last row.
            // (With more, a helper held up on an early row may let all come at once.)
            if (threads == 1) CHECK(sink.sizes.size() >= 2);
        }
    }
    for (int rows : {1, 2, 7}) {  // fewer rows than a block: all in one call at the end
        rt::Scene scene = file_scenes(5, rows).front().second;
        RecordingSink sink;
        rt::render_to<double>(scene, sink, 2);
        CHECK(sink.bytes == rt::render_reference<double>(scene, 1).rgb);
        CHECK_EQ(sink.sizes.size(), std::size_t{1});
    }
}

// A sink that takes its time: its first call holds up the writing for 30 ms, far longer
// than the rest of the render takes. render_to() keeps only a ring of rows, so threads
// that run ahead must wait for their rows' slots to be written, and not overwrite them.
struct SlowSink final : rt::RowSink {
    RecordingSink recorded;
    bool first = true;
    void write_rows(const std::uint8_t* data, std::size_t size) override {
        if (first) std::this_thread::sleep_for(std::chrono::milliseconds(30));
        first = false;
        recorded.write_rows(data, size);
    }
};

TEST(rows_wait_for_a_slow_sink) {
    for (const auto& [name, scene] : file_scenes(300, 400)) {
        const rt::Image image = rt::render_reference<double>(scene, 1);
        for (unsigned threads : {1U, 2U, 4U}) {
            SlowSink sink;
            rt::render_to<double>(scene, sink, threads);
            const bool same = sink.recorded.bytes == image.rgb;
            if (!same) std::cerr << name << ": " << threads << " threads, slow sink: the image differs\n";
            CHECK(same);
        }
    }
}

TEST(any_thread_count_gives_the_same_bytes) {
    for (const auto& [name, scene] : file_scenes(97, 61)) {
        const rt::Image one = rt::render<double>(scene, 1);
        for (unsigned threads : {2U, 3U, 5U, 16U, 64U, 200U}) {
            const bool same = rt::render<double>(scene, threads).rgb == one.rgb;
            if (!same) std::cerr << name << ": " << threads << " threads differ from 1\n";
            CHECK(same);
        }
    }
}
