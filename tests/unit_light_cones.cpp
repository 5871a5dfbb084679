// LightCones rules a sphere out only where no shadow ray it is asked about can be
// blocked by the ellipsoid inside it: for random scenes (a room enclosing the lights,
// thin and negated ellipsoids, lights next to and inside spheres), packets of points on
// the ellipsoids and anywhere in space, every (lane, ellipsoid) pair that lanes() leaves
// out, and every ellipsoid that packet() leaves out for the packet's ball, must give
// intersect()'s "not blocked" (no root in (0.001, 1)). Both must also rule out a good
// share, and a ball with a NaN coordinate must rule out nothing.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/flat_sweep/light_cones.h"
#include "raytracer/flat_sweep/sphere_bounds.h"
#include "raytracer/reference/ellipsoid.h"

namespace {

constexpr int N = 8;
constexpr std::uint64_t kLane[N] = {1, 2, 4, 8, 16, 32, 64, 128};

}  // namespace

TEST(light_cones_rule_out_only_ellipsoids_that_cannot_block) {
    long long wrong_lanes = 0, wrong_packets = 0, lane_pairs = 0, lanes_out = 0, packet_pairs = 0,
              packets_out = 0, blocked = 0;
    for (unsigned seed = 1; seed <= 66; ++seed) {
        std::mt19937 g(seed);
        const bool crowd = seed > 60;  // 65 to 202 ellipsoids: EllipsoidSet's later words
        const std::vector<rt::Ellipsoid<double>> ellipsoids =
            crowd ? random_room_scene(g, 65, 138) : random_room_scene(g);
        std::vector<rt::Vec3<double>> lights(4);
        for (rt::Vec3<double>& light : lights)
            light = {uniform(g, -6, 6), uniform(g, -6, 6), uniform(g, -12, 2)};
        lights[3] = ellipsoids[1 + g() % (ellipsoids.size() - 1)].centre;  // inside an ellipsoid
        const rt::SphereBounds<double> bounds(ellipsoids);
        std::vector<rt::BoundingSphere<double>> spheres;
        for (std::size_t i = 0; i < bounds.size(); ++i) spheres.push_back(bounds.sphere(i));
        const rt::LightCones<double> cones(spheres, lights);
        CHECK(cones.usable());
        for (int packet = 0; packet < 60; ++packet) {
            // N points on one ellipsoid near each other, on different ellipsoids, or in space.
            double px[N], py[N], pz[N], fx[N], fy[N], fz[N], d[N];
            const std::size_t on = g() % ellipsoids.size();
            const double spread = packet % 3 == 0 ? 0.05 : 1.0;
            const rt::Vec3<double> around{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)};
            for (int k = 0; k < N; ++k) {
                rt::Vec3<double> u =
                    around +
                    rt::Vec3<double>{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)} * spread;
                u = u * (1 / std::sqrt(dot(u, u)));
                const rt::Ellipsoid<double>& e = ellipsoids[packet % 3 == 1 ? g() % ellipsoids.size() : on];
                const rt::Vec3<double> point =
                    packet % 5 == 4
                        ? rt::Vec3<double>{uniform(g, -8, 8), uniform(g, -8, 8), uniform(g, -14, 3)}
                        : e.centre + u * e.scale;
                px[k] = point.x, py[k] = point.y, pz[k] = point.z;
            }
            const auto ball = rt::LightCones<double>::ball<N>(px, py, pz);
            CHECK(ball.usable);
            for (std::size_t l = 0; l < lights.size(); ++l) {
                for (int k = 0; k < N; ++k) {
                    fx[k] = -(lights[l].x - px[k]), fy[k] = -(lights[l].y - py[k]),
                    fz[k] = -(lights[l].z - pz[k]);
                    d[k] = std::sqrt(fx[k] * fx[k] + fy[k] * fy[k] + fz[k] * fz[k]);
                }
                // The width the renderer takes for this scene, and the widest.
                const rt::WideSet reached =
                    cones.packet(l, lights[l], ball, rt::WideSet::first(rt::WideSet::kCapacity));
                if (!crowd) {
                    const rt::NarrowSet narrow = cones.packet(l, lights[l], ball, rt::NarrowSet::first(64));
                    for (std::size_t j = 0; j < 64; ++j) CHECK(narrow.contains(j) == reached.contains(j));
                }
                for (std::size_t j = ellipsoids.size(); j < rt::WideSet::kCapacity; ++j)
                    CHECK(!reached.contains(j));  // only spheres there are
                for (std::size_t j = 0; j < ellipsoids.size(); ++j) {
                    const std::uint64_t lanes = cones.lanes<N>(l, j, fx, fy, fz, d, kLane);
                    const bool packet_in = reached.contains(j);
                    ++packet_pairs;
                    packets_out += !packet_in;
                    for (int k = 0; k < N; ++k) {
                        const rt::Vec3<double> point{px[k], py[k], pz[k]};
                        const bool b = blocks(ellipsoids[j], point, lights[l] - point);
                        const bool lane_in = (lanes & kLane[k]) != 0;
                        ++lane_pairs;
                        lanes_out += !lane_in;
                        blocked += b;
                        wrong_lanes += b && !lane_in;
                        wrong_packets += b && !packet_in;
                    }
                }
            }
        }
    }
    CHECK(wrong_lanes == 0);
    CHECK(wrong_packets == 0);
    CHECK(blocked > lane_pairs / 100);      // the scenes do cast shadows
    CHECK(lanes_out > lane_pairs / 2);      // the lane test rules out a good share
    CHECK(packets_out > packet_pairs / 4);  // and so does the ball
}

TEST(light_cones_rule_out_nothing_for_a_ball_with_a_nan) {
    const std::vector<rt::BoundingSphere<double>> spheres = {{0, 0, -5, 1}, {3, 0, -5, 1}};
    const std::vector<rt::Vec3<double>> lights = {{0, 5, -5}};
    const rt::LightCones<double> cones(spheres, lights);
    const rt::NarrowSet both = rt::NarrowSet::first(2), every = rt::NarrowSet::first(64);
    double px[N], py[N], pz[N];
    for (int k = 0; k < N; ++k) px[k] = 10 + k, py[k] = -10, pz[k] = 10;
    CHECK(cones.packet(0, lights[0], rt::LightCones<double>::ball<N>(px, py, pz), both).empty());  // far away
    px[3] = std::numeric_limits<double>::quiet_NaN();
    const auto ball = rt::LightCones<double>::ball<N>(px, py, pz);
    CHECK(!ball.usable);
    CHECK(cones.packet(0, lights[0], ball, both) == both);
    CHECK(cones.packet(0, lights[0], ball, every) == both);  // only spheres there are
    // A light inside the ball: nothing ruled out, but only spheres there are.
    px[3] = 0;
    CHECK(cones.packet(0, {5, -10, 10}, rt::LightCones<double>::ball<N>(px, py, pz), every) == both);
    // A NaN lane may meet every sphere.
    double fx[N], fy[N], fz[N], d[N];
    for (int k = 0; k < N; ++k) fx[k] = 0, fy[k] = 1, fz[k] = 0, d[k] = 1;  // away from both
    fx[5] = std::numeric_limits<double>::quiet_NaN();
    d[5] = fx[5];
    CHECK(cones.lanes<N>(0, 0, fx, fy, fz, d, kLane) == kLane[5]);
    CHECK(cones.lanes<N>(0, 1, fx, fy, fz, d, kLane) == kLane[5]);
}
