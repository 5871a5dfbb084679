// PairBlockers leaves ellipsoid j out of the set of (ellipsoid i, light l) only where no
// shadow ray from a point of i's bounding sphere to l can be blocked by j: for random
// scenes (a room enclosing lights among them, thin and negated ellipsoids), points on i
// and inside its bounding sphere, every j outside the set must give intersect()'s "not
// blocked" (no root in (0.001, 1)); and the sets must leave out a good share. Some
// scenes hold more ellipsoids than a 64-bit word (a WideSet's later words).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/flat_sweep/enclosures.h"
#include "raytracer/flat_sweep/pair_blockers.h"
#include "raytracer/flat_sweep/sphere_bounds.h"
#include "raytracer/reference/ellipsoid.h"

TEST(pair_blockers_leave_out_only_ellipsoids_that_cannot_block) {
    long long wrong = 0, left_out = 0, pairs = 0, blocked = 0;
    for (unsigned seed = 1; seed <= 46; ++seed) {
        std::mt19937 g(seed);
        const bool crowd = seed > 40;  // 65 to 202 ellipsoids
        std::vector<rt::Ellipsoid<double>> ellipsoids =
            crowd ? random_room_scene(g, 65, 138) : random_room_scene(g);
        rt::SphereSpec wall{};  // an ellipsoid through the room's wall
        wall.centre = {13.5, 0, -5}, wall.scale = {1.5, 1, 1};
        ellipsoids[1] = rt::make_ellipsoid<double>(wall);
        std::vector<rt::Vec3<double>> lights(4);
        for (rt::Vec3<double>& light : lights)
            light = {uniform(g, -6, 6), uniform(g, -6, 6), uniform(g, -12, 2)};
        const rt::SphereBounds<double> bounds(ellipsoids);
        const rt::Enclosures<double> enclosures(ellipsoids, lights);
        std::vector<rt::BoundingSphere<double>> spheres;
        for (std::size_t i = 0; i < bounds.size(); ++i) spheres.push_back(bounds.sphere(i));
        const rt::PairBlockers<double> sets(spheres, ellipsoids, lights, [&](std::size_t l, std::size_t j) {
            return enclosures.light_within(l, j);
        });
        CHECK(sets.usable());
        for (std::size_t i = 0; i < ellipsoids.size(); i += crowd ? 5 : 1)
            for (std::size_t l = 0; l < lights.size(); ++l) {
                // In the width the renderer takes for this scene.
                auto in_set = [&](std::size_t j) {
                    return crowd ? sets.set<rt::WideSet>(i, l).contains(j)
                                 : sets.set<rt::NarrowSet>(i, l).contains(j);
                };
                for (std::size_t j = 0; j < ellipsoids.size(); ++j) {
                    ++pairs;
                    if (in_set(j)) continue;
                    ++left_out;
                    for (int round = 0; round < (crowd ? 20 : 200); ++round) {
                        // A point on i (rounded) or anywhere inside its bounding sphere.
                        rt::Vec3<double> u{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)};
                        u = u * (1 / std::sqrt(dot(u, u)));
                        const rt::Ellipsoid<double>& e = ellipsoids[i];
                        const rt::BoundingSphere<double>& s = spheres[i];
                        const rt::Vec3<double> point =
                            round % 2 ? e.centre + u * e.scale
                                      : rt::Vec3<double>{s.x, s.y, s.z} + u * (s.radius * uniform(g, 0, 1));
                        const bool b = blocks(ellipsoids[j], point, lights[l] - point);
                        wrong += b;
                        blocked += b;
                    }
                }
            }
    }
    CHECK(wrong == 0);
    CHECK(left_out > pairs / 4);  // the sets leave out a good share
    CHECK(blocked == 0);
}
