// The tree's bundle queries (Bvh::closest() and Bvh::occluded() for the lanes of a
// tile, whitted_tiles.h; Bvh::closest() for a block of eye rays, eye_block.h) answer,
// lane by lane, as BruteForce answers each ray alone: on crowds of thin, tiny, huge, negated, touching and
// far ellipsoids; for bundles tight and wide, with directions that straddle zero or hold +0 and -0 on one
// axis, with lights on a surface, and with every subset of lanes.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/accel/blocker_hints.h"
#include "raytracer/accel/bvh.h"
#include "raytracer/accel/exact_culling.h"
#include "raytracer/accel/light_shells.h"
#include "raytracer/bit_scan.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/spec_rules.h"
#include "stress_scenes.h"

namespace {

constexpr int kLanes = 16;

template <typename Real>
struct Crowd {
    std::vector<rt::Ellipsoid<Real>> all;
    std::vector<rt::Vec3<Real>> lights;
};

// n ellipsoids of the kinds the boxes' margins must hold for, and the scene's lights.
template <typename Real>
Crowd<Real> crowd(unsigned seed, int n) {
    std::mt19937 g(seed);
    const rt::Scene s = stress::random_scene(seed);
    Crowd<Real> c;
    for (const rt::SphereSpec& e : s.spheres) c.all.push_back(rt::make_ellipsoid<Real>(e));
    while (static_cast<int>(c.all.size()) < n) {
        rt::SphereSpec e = s.spheres[g() % s.spheres.size()];
        // Odd seeds: also ellipsoids so thin that the scene is beyond their guard
        // distance (bvh.h), where bundles go ray by ray; even seeds: the bundled path.
        const unsigned kind = seed % 2 ? g() % 6 : 1 + g() % 5;
        if (seed % 2 == 0 && kind == 2) continue;
        const double size = kind == 0 ? 1e-5 : kind == 1 ? 3 : uniform(g, 0.02, 0.6);
        e.centre = {uniform(g, -5, 5), uniform(g, -5, 5), uniform(g, -14, 1)};
        e.scale = {size * uniform(g, 0.3, 1), size * uniform(g, 0.3, 1), size * uniform(g, 0.3, 1)};
        if (kind == 2) e.scale.z = 1e-7;        // paper-thin
        if (kind == 3) e.scale.x = -e.scale.x;  // negated
        if (kind == 4) {                        // touching the previous one
            const rt::Ellipsoid<Real>& last = c.all.back();
            e.centre = rt::Vec3<double>::from(last.centre) +
                       rt::Vec3<double>{double(last.scale.x) + e.scale.x, 0, 0};
        }
        c.all.push_back(rt::make_ellipsoid<Real>(e));
    }
    for (const rt::LightSpec& l : s.lights) c.lights.push_back(rt::Vec3<Real>::from(l.position));
    return c;
}

// A point on e's surface in direction u from its centre.
template <typename Real>
rt::Vec3<Real> on_surface(const rt::Ellipsoid<Real>& e, const rt::Vec3<Real>& u) {
    return e.centre + normalize(u) * e.scale;
}

// Bundles of shadow rays from patches of a surface (tight, or spread over the whole
// ellipsoid) to a light (a scene light, a point on another surface, or one on the
// patch's own ellipsoid), against each lane's BruteForce::occluded(); half of them told,
// as the tiles tell them, which lanes their own ellipsoid cannot block
// (leaves_own_ellipsoid()), which BruteForce does not skip. cleared counts those lanes.
template <typename Real>
int shadow_lanes_differing(const Crowd<Real>& c, unsigned seed, int bundles, long& cleared) {
    using V = rt::Vec3<Real>;
    const rt::BruteForce<Real> plain(c.all);
    const rt::Bvh<Real> tree(c.all);
    std::mt19937 g(seed);
    int differing = 0;
    std::uint32_t hint = rt::kNoEllipsoid;  // carried from bundle to bundle, as in a render
    for (int b = 0; b < bundles; ++b) {
        // At times any ellipsoid, as a hint of another pair's (BlockerHints) may be.
        if (g() % 4 == 0) hint = static_cast<std::uint32_t>(g() % c.all.size());
        const auto own = static_cast<std::uint32_t>(g() % c.all.size());
        const rt::Ellipsoid<Real>& on = c.all[own];
        const double spread = g() % 2 ? 0.01 : 1.0;
        const V u0{Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1))};
        V points[kLanes];
        for (V& p : points)
            p = on_surface(on, u0 + V{Real(uniform(g, -spread, spread)), Real(uniform(g, -spread, spread)),
                                      Real(uniform(g, -spread, spread))});
        const unsigned kind = g() % 3;
        const V light = kind == 0   ? c.lights[g() % c.lights.size()]
                        : kind == 1 ? on_surface(c.all[g() % c.all.size()], points[0] - on.centre)
                                    : on_surface(on, -u0);
        const auto lanes = static_cast<unsigned>(g() & 0xFFFF);
        unsigned own_clear = 0;
        const bool tell = g() % 2 == 0;
        for (int k = 0; k < kLanes && tell; ++k) {  // as whitted_tiles.h computes it
            using std::abs;
            const V to_centre = points[k] - on.centre;
            const V scaled = to_centre / on.scale_squared;
            const V to_light = light - points[k];
            const Real distance = length(to_light);
            const Real n_dot_l = dot(normalize(scaled), to_light * (Real(1) / distance));
            const V mapped = to_centre / on.scale;
            const Real abs_c = abs(dot(mapped, mapped) - Real(1));
            if (rt::leaves_own_ellipsoid<Real>(length(scaled), distance, n_dot_l, abs_c))
                own_clear |= 1U << k;
        }
        cleared += rt::bit_count(own_clear & lanes);
        rt::ClearedLanes told;
        told.add(own, own_clear & lanes);
        const unsigned blocked = tree.occluded(points, light, lanes, hint, told);
        for (int k = 0; k < kLanes; ++k) {
            if ((lanes >> k & 1U) == 0) continue;
            std::uint32_t plain_hint = rt::kNoEllipsoid;
            differing +=
                plain.occluded(points[k], light - points[k], plain_hint) != ((blocked >> k & 1U) != 0);
        }
    }
    return differing;
}

// Blocks of eye rays (Bvh::closest() for an EyeBlock: the tiles' first bounce), of 1-4
// rows and 1-8 columns, aimed at an ellipsoid or anywhere, with pixels a hair apart or
// far apart, some columns through x = 0 or -0, against each pixel's
// BruteForce::closest() from the camera. hits counts the pixels that see something.
template <typename Real>
int eye_pixels_differing(const Crowd<Real>& c, unsigned seed, int blocks, long& hits) {
    using V = rt::Vec3<Real>;
    constexpr int kRows = 4, kColumns = 8;
    const rt::BruteForce<Real> plain(c.all);
    const rt::Bvh<Real> tree(c.all);
    std::mt19937 g(seed);
    int differing = 0;
    for (int k = 0; k < blocks; ++k) {
        const Real near_z = -Real(g() % 2 ? 1 : uniform(g, 0.05, 4));
        const V aim = c.all[g() % c.all.size()].centre;
        // Where the aimed-at centre meets the near plane (anywhere, if behind the camera).
        const bool ahead = aim.z < 0 && g() % 4 != 0;
        double x0 = ahead ? double(aim.x * (near_z / aim.z)) : uniform(g, -3, 3);
        double y0 = ahead ? double(aim.y * (near_z / aim.z)) : uniform(g, -3, 3);
        const double step = g() % 2 ? uniform(g, 1e-4, 1e-2) : uniform(g, 0.02, 0.5);
        // A block across the image's centre lines, whose rays' x (or y) change sign:
        // Bvh::closest() takes it as one bundle a side.
        const unsigned across = g() % 4;
        if (across & 1U) x0 = step * uniform(g, -2, 2);
        if (across & 2U) y0 = step * uniform(g, 0, 3);
        const int rows = 1 + static_cast<int>(g() % kRows), columns = 1 + static_cast<int>(g() % kColumns);
        Real x[kColumns], y[kRows];
        const int centre = columns / 2;  // the aimed-at column
        for (int i = 0; i < columns; ++i) x[i] = Real(x0 + step * (i - centre));
        for (int b = 0; b < rows; ++b) y[b] = Real(y0 - step * b);
        if (g() % 8 == 0) x[g() % columns] = g() % 2 ? Real(0) : -Real(0);
        rt::EyeBlock<Real, kRows, kColumns> block(x, columns, y, rows, near_z);
        tree.closest(block);
        for (int b = 0; b < rows; ++b)
            for (int i = 0; i < columns; ++i) {
                const rt::NearestHit<Real> want = plain.closest({}, {x[i], y[b], near_z}, rt::kEyeRayMinT);
                const rt::NearestHit<Real> got = block.tried() ? block.hit(b, i) : rt::NearestHit<Real>{};
                hits += want.found();
                differing += !(got.ellipsoid == want.ellipsoid &&
                               (!want.found() || (got.t == want.t && got.inside == want.inside)));
            }
    }
    return differing;
}

// Bundles of rays from one origin (the camera, a surface point, anywhere), or from a
// patch of a surface (a tile's mirrored rays: a bundle where their directions are
// narrow_directions() or the scene has at most as many ellipsoids as the bundle has lanes, else ray
// by ray), in a narrow or wide cone, some with a direction component of +0 or -0,
// against each lane's BruteForce::closest(). mirrored: only narrow bundles from patches.
template <typename Real>
int closest_lanes_differing(const Crowd<Real>& c, unsigned seed, int bundles, bool mirrored = false) {
    using V = rt::Vec3<Real>;
    const rt::BruteForce<Real> plain(c.all);
    const rt::Bvh<Real> tree(c.all);
    std::mt19937 g(seed);
    int differing = 0;
    for (int b = 0; b < bundles; ++b) {
        const unsigned kind = mirrored ? 3 : g() % 5;
        const rt::Ellipsoid<Real>& from = c.all[g() % c.all.size()];
        const V u0{Real(uniform(g, -1, 1)), Real(1), Real(0.5)};
        const V origin = kind == 0 ? V{}
                         : kind == 1
                             ? on_surface(from, u0)
                             : V{Real(uniform(g, -6, 6)), Real(uniform(g, -6, 6)), Real(uniform(g, -6, 6))};
        const V aim = c.all[g() % c.all.size()].centre - origin;
        const double spread = mirrored ? 0.02 : g() % 2 ? 0.02 : 0.5;
        V origins[kLanes], directions[kLanes];
        const double patch = g() % 2 ? 0.01 : 0.5;
        for (int k = 0; k < kLanes; ++k) {
            origins[k] = kind < 3 ? origin
                                  : on_surface(from, u0 + V{Real(uniform(g, -patch, patch)),
                                                            Real(uniform(g, -patch, patch)), Real(0)});
            // The camera as 0 and as -0 in turn: one point, but not the same bits (the
            // root solver may take a zero's sign, as in the room around the camera).
            if (kind == 4) origins[k] = k % 2 ? V{} : V{-Real(0), -Real(0), -Real(0)};
            directions[k] = aim + V{Real(uniform(g, -spread, spread)), Real(uniform(g, -spread, spread)),
                                    Real(uniform(g, -spread, spread))} *
                                      Real(length(aim));
            if (!mirrored && g() % 8 == 0) directions[k].x = k % 2 ? Real(0) : -Real(0);
        }
        const unsigned lanes = b % 2 ? 0xFFFFU : static_cast<unsigned>(g() & 0xFFFF);  // half of them all 16
        for (const double min_t : {1.0, 0.001, 0.0001}) {
            rt::NearestHit<Real> hits[kLanes];
            tree.closest(origins, directions, lanes, min_t, hits);
            for (int k = 0; k < kLanes; ++k) {
                if ((lanes >> k & 1U) == 0) continue;
                const rt::NearestHit<Real> want = plain.closest(origins[k], directions[k], min_t);
                differing += !(hits[k].ellipsoid == want.ellipsoid &&
                               (!want.found() || (hits[k].t == want.t && hits[k].inside == want.inside)));
            }
        }
    }
    return differing;
}

// A crowd inside a mirror room (a shell around it all) whose lights lie inside the shell,
// just inside it, on it and just outside it; bundles of shadow rays from patches of the
// shell's inner surface, of other surfaces and of points around the shell's surface, told
// which lanes the shells that hold their light hold (light_shells.h, as the tiles tell
// them), against each lane's BruteForce::occluded(). skipped counts the lanes told.
template <typename Real>
int shell_lanes_differing(Crowd<Real> c, unsigned seed, int bundles, long& skipped) {
    using V = rt::Vec3<Real>;
    std::mt19937 g(seed);
    c.all.push_back(rt::make_ellipsoid<Real>(rt::SphereSpec{{0, 0, -6}, {9, 8, 11}, {}, 0, 0, 0, 0.8, 1, 0}));
    const rt::Ellipsoid<Real>& room = c.all.back();
    for (const double radius : {0.3, 0.9995, 0.999, 1.0, 1.0005, 1.01})  // in units of the room's scales
        for (int i = 0; i < 3; ++i)
            c.lights.push_back(room.centre + normalize(V{Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1)),
                                                         Real(uniform(g, -1, 1))}) *
                                                 room.scale * Real(radius));
    const rt::BruteForce<Real> plain(c.all);
    const rt::Bvh<Real> tree(c.all);
    const rt::LightShells<Real> shells(tree, c.lights);
    int differing = 0;
    std::uint32_t hint = rt::kNoEllipsoid;
    for (int b = 0; b < bundles; ++b) {
        const unsigned kind = g() % 3;  // the room's surface, another's, around the room's
        const rt::Ellipsoid<Real>& on = kind == 1 ? c.all[g() % (c.all.size() - 1)] : room;
        const double spread = g() % 2 ? 0.01 : 1.0;
        const V u0{Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1))};
        rt::Vec3<rt::Lanes<Real, kLanes>> point_lanes;
        V points[kLanes];
        for (int k = 0; k < kLanes; ++k) {
            const V p =
                on_surface(on, u0 + V{Real(uniform(g, -spread, spread)), Real(uniform(g, -spread, spread)),
                                      Real(uniform(g, -spread, spread))});
            points[k] = kind == 2 ? on.centre + (p - on.centre) * Real(uniform(g, 0.999, 1.001)) : p;
            set_lane(point_lanes, k, points[k]);
        }
        const std::size_t li = g() % c.lights.size();
        const auto lanes = static_cast<unsigned>(g() & 0xFFFF);
        rt::ClearedLanes told;
        for (unsigned m = shells.of_light(li); m != 0; m &= m - 1) {
            const int s = rt::lowest_bit(m);
            const unsigned held = lanes & static_cast<unsigned>(shells.holding(s, point_lanes));
            told.add(shells.ellipsoid(s), held);
            skipped += rt::bit_count(held);
        }
        const unsigned blocked = tree.occluded(points, c.lights[li], lanes, hint, told);
        for (int k = 0; k < kLanes; ++k) {
            if ((lanes >> k & 1U) == 0) continue;
            std::uint32_t plain_hint = rt::kNoEllipsoid;
            differing +=
                plain.occluded(points[k], c.lights[li] - points[k], plain_hint) != ((blocked >> k & 1U) != 0);
        }
    }
    return differing;
}

// Bvh::may_meet() over ranges of directions from one origin (the camera, or anywhere),
// narrow and wide, some straddling zero on an axis: where it says no, no ray of 64 in the
// range, its corners among them, hits anything (BruteForce::closest()). misses counts
// the ranges it rules out, so that the test has something to check.
template <typename Real>
int may_meet_wrong(const Crowd<Real>& c, unsigned seed, int ranges, long& misses) {
    using V = rt::Vec3<Real>;
    using C = rt::AtLeastDouble<Real>;
    const rt::BruteForce<Real> plain(c.all);
    const rt::Bvh<Real> tree(c.all);
    std::mt19937 g(seed);
    int wrong = 0;
    for (int r = 0; r < ranges; ++r) {
        const V origin =
            g() % 2 ? V{} : V{Real(uniform(g, -6, 6)), Real(uniform(g, -6, 6)), Real(uniform(g, -6, 6))};
        const double width = g() % 2 ? 0.01 : 0.3;
        C lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            const double middle = uniform(g, -1, 1);
            lo[a] = C(Real(middle - uniform(g, 0, width))), hi[a] = C(Real(middle + uniform(g, 0, width)));
        }
        if (tree.may_meet(origin, lo, hi)) continue;
        ++misses;
        for (int k = 0; k < 64; ++k) {
            auto pick = [&](int a) {
                return k < 8 ? ((k >> a) & 1 ? hi[a] : lo[a]) : C(uniform(g, double(lo[a]), double(hi[a])));
            };
            const V d{Real(pick(0)), Real(pick(1)), Real(pick(2))};
            for (const double min_t : {1.0, 0.0001}) wrong += plain.closest(origin, d, min_t).found();
        }
    }
    return wrong;
}
}  // namespace

TEST(bvh_shadow_bundles_match_brute_force) {
    long cleared = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
        const int n = 70 + static_cast<int>(seed) * 40;
        CHECK_EQ(shadow_lanes_differing(crowd<float>(seed, n), seed, 600, cleared), 0);
        CHECK_EQ(shadow_lanes_differing(crowd<double>(seed, n), seed, 600, cleared), 0);
        CHECK_EQ(shadow_lanes_differing(crowd<long double>(seed, n), seed, 300, cleared), 0);
    }
    std::cout << "  own ellipsoid skipped for " << cleared << " lanes\n";
    CHECK(cleared > 10000);
}

// A shadow bundle's edges converge on its light: on an axis where the light lies between
// the points' planes, d_lo > 0 > d_hi, and a lane's component there may be 0. With the
// light inside the points' box on every axis, no axis keeps the lanes' directions away
// from 0, and boxes must not cull them (make_slab_ray()'s least): the query then tries
// every ellipsoid, as where a direction may map below the normal range.
TEST(slab_rays_of_converging_edges_around_the_light_do_not_cull) {
    using C = double;
    const C o_lo[3] = {-1, -1, -1}, o_hi[3] = {1, 1, 1}, least = 1e-300;
    rt::SlabRay<C> ray;
    const C around_lo[3] = {1, 1, 1}, around_hi[3] = {-1, -1, -1};  // the light at 0
    CHECK(!rt::make_slab_ray(o_lo, o_hi, around_lo, around_hi, least, ray));
    const C beyond_lo[3] = {3, 1, 1}, beyond_hi[3] = {1, -1, -1};  // at x = 2: every x >= 1
    CHECK(rt::make_slab_ray(o_lo, o_hi, beyond_lo, beyond_hi, least, ray));
}

// Each (ellipsoid, light) pair keeps its own hint while the pairs fit the table; past
// kMaxSlots pairs share slots, and a hint read is one some pair stored, or none.
TEST(blocker_hints_keep_a_hint_per_pair) {
    const rt::BlockerHints hints(1000, 7);
    CHECK_EQ(hints.load(999, 6), rt::kNoEllipsoid);
    for (std::uint32_t e = 0; e < 1000; ++e)
        for (std::size_t l = 0; l < 7; ++l) hints.store(e, l, e * 7 + static_cast<std::uint32_t>(l));
    int wrong = 0;
    for (std::uint32_t e = 0; e < 1000; ++e)
        for (std::size_t l = 0; l < 7; ++l)
            wrong += hints.load(e, l) != e * 7 + static_cast<std::uint32_t>(l);
    CHECK_EQ(wrong, 0);
    const rt::BlockerHints shared(rt::BlockerHints::kMaxSlots, 3);
    shared.store(5, 1, 42);
    CHECK_EQ(shared.load(5, 1), 42U);
    CHECK_EQ(shared.load(5, 2), rt::kNoEllipsoid);
    // Ellipsoid 5 + kMaxSlots shares ellipsoid 5's slots.
    const std::uint32_t far = 5 + static_cast<std::uint32_t>(rt::BlockerHints::kMaxSlots);
    CHECK_EQ(shared.load(far, 1), 42U);
}

TEST(bvh_closest_bundles_match_brute_force) {
    for (unsigned seed = 1; seed <= 8; ++seed) {
        const int n = 70 + static_cast<int>(seed) * 40;
        CHECK_EQ(closest_lanes_differing(crowd<float>(seed, n), seed, 400), 0);
        CHECK_EQ(closest_lanes_differing(crowd<double>(seed, n), seed, 400), 0);
        CHECK_EQ(closest_lanes_differing(crowd<long double>(seed, n), seed, 200), 0);
    }
}

// The same for blocks of eye rays; odd seeds put ellipsoids beyond the camera's guard
// distance, where the block tries each ellipsoid of the leaves it reaches unculled.
TEST(bvh_eye_blocks_match_brute_force) {
    long hits = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
        const int n = 30 + static_cast<int>(seed) * 40;
        CHECK_EQ(eye_pixels_differing(crowd<float>(seed, n), seed, 600, hits), 0);
        CHECK_EQ(eye_pixels_differing(crowd<double>(seed, n), seed, 800, hits), 0);
        CHECK_EQ(eye_pixels_differing(crowd<long double>(seed, n), seed, 300, hits), 0);
    }
    std::cout << "  eye pixels that see an ellipsoid: " << hits << "\n";
    CHECK(hits > 20000);
}

// Copies of ellipsoids before and after them: equal roots, where the lower index must
// win whichever the descent tries first. In double the camera is within every guard
// (the blocks cull); in float (a guard of 50 smallest scales) beyond the thin ones', where
// the block must go ray by ray: culling there found 70-117 wrong pixels.
template <typename Real>
long eye_ties_differing(unsigned seed, long& hits) {
    Crowd<Real> c = crowd<Real>(seed, 60);
    const std::vector<rt::Ellipsoid<Real>> first(c.all.begin(), c.all.begin() + 20);
    c.all.insert(c.all.end(), first.begin(), first.end());
    c.all.insert(c.all.begin(), first.begin(), first.end());
    return eye_pixels_differing(c, seed, 1500, hits);
}
TEST(bvh_eye_blocks_break_ties_as_brute_force) {
    long hits = 0;
    for (unsigned seed = 2; seed <= 8; seed += 2) CHECK_EQ(eye_ties_differing<double>(seed, hits), 0);
    for (unsigned seed = 1; seed <= 8; ++seed) CHECK_EQ(eye_ties_differing<float>(seed, hits), 0);
    CHECK(hits > 5000);
}

// The same with a room centred on the camera, in which a ray from 0 and one from -0 start
// at opposite zeros of its unit space, where the root solver may take a zero's sign.
TEST(bvh_closest_bundles_from_0_and_minus_0_match_brute_force) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
        const rt::SphereSpec room{{0, 0, 0}, {7, 5, 9}, {}, 0, 0, 0, 0.5, 1, 0};
        Crowd<float> f = crowd<float>(seed, 100);
        f.all.insert(f.all.begin(), rt::make_ellipsoid<float>(room));
        CHECK_EQ(closest_lanes_differing(f, seed, 400), 0);
        Crowd<double> d = crowd<double>(seed, 100);
        d.all.insert(d.all.begin(), rt::make_ellipsoid<double>(room));
        CHECK_EQ(closest_lanes_differing(d, seed, 400), 0);
        Crowd<long double> l = crowd<long double>(seed, 100);
        l.all.insert(l.all.begin(), rt::make_ellipsoid<long double>(room));
        CHECK_EQ(closest_lanes_differing(l, seed, 200), 0);
    }
}

// Rays from different origins in narrow cones, which go as a bundle in any scene.
TEST(bvh_closest_narrow_bundles_of_mirrored_rays_match_brute_force) {
    for (unsigned seed = 1; seed <= 8; ++seed) {
        const int n = 70 + static_cast<int>(seed) * 40;
        CHECK_EQ(closest_lanes_differing(crowd<float>(seed, n), seed, 300, true), 0);
        CHECK_EQ(closest_lanes_differing(crowd<double>(seed, n), seed, 400, true), 0);
        CHECK_EQ(closest_lanes_differing(crowd<long double>(seed, n), seed, 200, true), 0);
    }
}

// Scenes of at most 16 ellipsoids, where rays from different origins go as a bundle too.
TEST(bvh_closest_bundles_of_mirrored_rays_match_brute_force) {
    for (unsigned seed = 1; seed <= 12; ++seed) {
        const std::size_t n = std::size_t{2} + seed;
        Crowd<float> narrow = crowd<float>(seed, static_cast<int>(n));
        narrow.all.resize(std::min(narrow.all.size(), n));
        CHECK_EQ(closest_lanes_differing(narrow, seed, 1000), 0);
        Crowd<double> c = crowd<double>(seed, static_cast<int>(n));
        c.all.resize(std::min(c.all.size(), n));
        CHECK_EQ(closest_lanes_differing(c, seed, 1500), 0);
        Crowd<long double> wide = crowd<long double>(seed, static_cast<int>(n));
        wide.all.resize(std::min(wide.all.size(), n));
        CHECK_EQ(closest_lanes_differing(wide, seed, 500), 0);
    }
}

TEST(shells_skip_only_shadow_rays_they_cannot_block) {
    long skipped = 0;
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const int n = 40 + static_cast<int>(seed) * 30;
        long none = 0;
        CHECK_EQ(shell_lanes_differing(crowd<float>(seed, n), seed, 300, none), 0);
        CHECK_EQ(none, 0);  // float: no shells (light_shells.h)
        CHECK_EQ(shell_lanes_differing(crowd<double>(seed, n), seed, 600, skipped), 0);
        CHECK_EQ(shell_lanes_differing(crowd<long double>(seed, n), seed, 300, skipped), 0);
    }
    std::cout << "  shells skipped for " << skipped << " lanes\n";
    CHECK(skipped > 10000);
}

TEST(bvh_may_meet_says_no_only_where_no_ray_hits) {
    long misses = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
        const int n = 20 + static_cast<int>(seed) * 30;
        CHECK_EQ(may_meet_wrong(crowd<float>(seed, n), seed, 2000, misses), 0);
        CHECK_EQ(may_meet_wrong(crowd<double>(seed, n), seed, 2000, misses), 0);
        CHECK_EQ(may_meet_wrong(crowd<long double>(seed, n), seed, 1000, misses), 0);
    }
    std::cout << "  ranges ruled out: " << misses << "\n";
    CHECK(misses > 500);
}
