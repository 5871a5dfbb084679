// The shadow tests of a packet's lanes at once (PacketTracer::lit_lanes()):
// prefilter_shadow_lanes() must never answer blocked or clear against intersect()'s
// answer, blocked_lanes() must give each lane blocks_segment()'s, and
// Enclosures::contains_segments() must give every lane contains_segment()'s, for random
// rays and for rays built to lie at the prefilter's margins (roots near 0.001 and 1
// give or take 1e-4, near-tangent lines, |o'|^2 near 1e4, |d'|^2 near 1e-4), where
// rounding would show.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/accel/shadow_prefilter.h"
#include "raytracer/flat_sweep/enclosures.h"
#include "raytracer/flat_sweep/hit_packet.h"
#include "raytracer/reference/ellipsoid.h"

namespace {

constexpr int N = rt::kPacket;

double pick(std::mt19937& g, const std::vector<double>& values) { return values[g() % values.size()]; }

std::vector<rt::Ellipsoid<double>> random_ellipsoids(std::mt19937& g, int count) {
    std::vector<rt::Ellipsoid<double>> ellipsoids;
    for (int i = 0; i < count; ++i) {
        rt::SphereSpec s{};
        s.centre = {uniform(g, -5, 5), uniform(g, -5, 5), uniform(g, -10, 0)};
        s.scale = {uniform(g, 0.1, 4), uniform(g, 0.1, 4), uniform(g, 0.1, 4)};
        if (i % 3 == 1) s.scale.y = -s.scale.y;
        if (i % 5 == 2) s.scale = {20, 15, 25};  // a room around the others
        ellipsoids.push_back(rt::make_ellipsoid<double>(s));
    }
    return ellipsoids;
}

struct Ray {
    rt::Vec3<double> point, to_light;
};

// A ray against ellipsoid e whose mapped line has h = 1 - |l|^2 (l: its point nearest
// the centre) and its near root at t_near (its far root at t_near + 2 sqrt(h) / length),
// with |d'| = length; rounding moves them a little, which is the point.
Ray ray_with_roots(std::mt19937& g, const rt::Ellipsoid<double>& e, double h, double t_near, double length) {
    using std::sqrt;
    rt::Vec3<double> u{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)};
    u = u * (1 / sqrt(dot(u, u)));
    rt::Vec3<double> w{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)};
    w = w - u * dot(w, u);
    w = w * (1 / sqrt(dot(w, w)));
    const rt::Vec3<double> nearest = w * sqrt(1 - h);
    const double half = h > 0 ? sqrt(h) : 0;
    const rt::Vec3<double> origin = nearest - u * (t_near * length + half);  // in unit space
    return {e.centre + origin * e.scale, (u * length) * e.scale};
}

Ray random_ray(std::mt19937& g, const rt::Ellipsoid<double>& e) {
    switch (g() % 4) {
        case 0:  // anywhere
            return {{uniform(g, -12, 12), uniform(g, -12, 12), uniform(g, -15, 5)},
                    {uniform(g, -20, 20), uniform(g, -20, 20), uniform(g, -20, 20)}};
        case 1: {  // at the prefilter's margins: roots and tangency near its limits
            const double h = pick(g, {-1e-6, 1e-3, 0.0, 0.3, 0.99}) * (1 + uniform(g, -1e-9, 1e-9)) +
                             uniform(g, -1e-15, 1e-15);
            const double t =
                pick(g, {0.001 - 1e-4, 0.001 + 1e-4, 1 - 1e-4, 1 + 1e-4, 0.001, 1.0, 0.5, -0.2}) +
                uniform(g, -1e-12, 1e-12);
            const double length = uniform(g, 0.02, 5);
            // The near root at t, or the far one (the other root then often out of range).
            const double spread = h > 0 ? 2 * std::sqrt(h) / length : 0;
            return ray_with_roots(g, e, h, g() % 2 ? t : t - spread, length);
        }
        case 2: {  // |o'|^2 near 1e4 or |d'|^2 near 1e-4, the roots in range or out
            const double t = pick(g, {0.5, 0.001 + 1e-4, 1 - 1e-4, -0.5, 1.5});
            const double h = uniform(g, -0.5, 0.9);
            if (g() % 2) {
                const double length = pick(g, {1e-2, 1e-2 * (1 + 1e-15), 1e-2 * (1 - 1e-15)});
                return ray_with_roots(g, e, h, t, length);
            }
            const double length = 100 / std::abs(t);  // the origin about 100 from the centre
            Ray r = ray_with_roots(g, e, h, t, length);
            rt::Vec3<double> o = (r.point - e.centre) / e.scale;
            o = o * (100 * (1 + uniform(g, -1e-15, 1e-15)) / std::sqrt(dot(o, o)));
            r.point = e.centre + o * e.scale;
            return r;
        }
        default: {  // from the surface (a hit point) outwards or inwards
            rt::Vec3<double> o{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)};
            o = o * (1 / std::sqrt(dot(o, o)));
            return {e.centre + o * e.scale, {uniform(g, -9, 9), uniform(g, -9, 9), uniform(g, -9, 9)}};
        }
    }
}

}  // namespace

TEST(lane_decide_never_contradicts_intersect) {
    std::mt19937 g(20261122);
    const std::vector<rt::Ellipsoid<double>> ellipsoids = random_ellipsoids(g, 12);
    long long contradicting = 0, blocked = 0, clear = 0, unsure = 0;
    for (int round = 0; round < 40000; ++round) {
        const std::size_t i = g() % ellipsoids.size();
        double px[N], py[N], pz[N], tx[N], ty[N], tz[N];
        Ray rays[N];
        for (int k = 0; k < N; ++k) {
            rays[k] = random_ray(g, ellipsoids[i]);
            px[k] = rays[k].point.x, py[k] = rays[k].point.y, pz[k] = rays[k].point.z;
            tx[k] = rays[k].to_light.x, ty[k] = rays[k].to_light.y, tz[k] = rays[k].to_light.z;
        }
        const rt::PrefilterAnswer lanes =
            rt::prefilter_shadow_lanes<N>(ellipsoids[i], px, py, pz, tx, ty, tz);
        CHECK_EQ(lanes.blocked & lanes.unsure, 0U);
        for (int k = 0; k < N; ++k) {
            if ((lanes.unsure >> k & 1U) != 0) {
                ++unsure;
                continue;
            }
            const bool says_blocked = (lanes.blocked >> k & 1U) != 0;
            (says_blocked ? blocked : clear) += 1;
            contradicting += says_blocked != blocks(ellipsoids[i], rays[k].point, rays[k].to_light);
        }
    }
    CHECK(contradicting == 0);
    // The rays reach every answer, the unsure ones (at the margins) included.
    CHECK(unsure > 1000);
    CHECK(clear > 1000);
    CHECK(blocked > 1000);
}

TEST(lane_enclosures_answer_as_the_scalar_test) {
    std::mt19937 g(7);
    const std::vector<rt::Ellipsoid<double>> ellipsoids = random_ellipsoids(g, 12);
    std::vector<rt::Vec3<double>> lights(6);
    for (rt::Vec3<double>& l : lights) l = {uniform(g, -6, 6), uniform(g, -6, 6), uniform(g, -12, 2)};
    const rt::Enclosures<double> enclosures(ellipsoids, lights);
    const std::uint64_t* lane = rt::kLaneBits<N>.bit;
    long long differing = 0, contained = 0;
    for (int round = 0; round < 20000; ++round) {
        const std::size_t i = g() % ellipsoids.size(), li = g() % lights.size();
        double px[N], py[N], pz[N];
        std::uint64_t expected = 0;
        for (int k = 0; k < N; ++k) {
            const rt::Vec3<double> p = random_ray(g, ellipsoids[i]).point;
            px[k] = p.x, py[k] = p.y, pz[k] = p.z;
            if (enclosures.contains_segment(p, li, i)) expected |= lane[k], ++contained;
        }
        differing += enclosures.contains_segments<N>(px, py, pz, li, i, lane) != expected;
    }
    CHECK(differing == 0);
    CHECK(contained > 1000);
}

// blocked_lanes(), the shadow decision both fast paths make for a set of lanes, gives
// each lane of the set blocks_segment()'s answer and no lane outside it: in double
// (the prefilter, then intersect() for the lanes it leaves) and in float (intersect()
// for every lane, in one vector loop).
template <typename Real>
void check_blocked_lanes(std::uint32_t seed) {
    std::mt19937 g(seed);
    const std::vector<rt::Ellipsoid<double>> ellipsoids = random_ellipsoids(g, 12);
    long long differing = 0, blocked = 0, open = 0;
    for (int round = 0; round < 20000; ++round) {
        const std::size_t i = g() % ellipsoids.size();
        rt::SphereSpec spec{};
        spec.centre = ellipsoids[i].centre, spec.scale = ellipsoids[i].scale;
        const rt::Ellipsoid<Real> e = rt::make_ellipsoid<Real>(spec);
        Real px[N], py[N], pz[N], tx[N], ty[N], tz[N];
        const rt::LaneBits lanes = g() & ((rt::LaneBits(1) << N) - 1);
        rt::LaneBits expected = 0;
        for (int k = 0; k < N; ++k) {
            const Ray r = random_ray(g, ellipsoids[i]);
            px[k] = Real(r.point.x), py[k] = Real(r.point.y), pz[k] = Real(r.point.z);
            tx[k] = Real(r.to_light.x), ty[k] = Real(r.to_light.y), tz[k] = Real(r.to_light.z);
            const bool blocks = rt::blocks_segment(e, rt::Vec3<Real>{px[k], py[k], pz[k]},
                                                   rt::Vec3<Real>{tx[k], ty[k], tz[k]});
            if ((lanes >> k & 1U) == 0) continue;
            (blocks ? blocked : open) += 1;
            expected |= blocks ? rt::LaneBits(1) << k : 0;
        }
        differing += rt::blocked_lanes<N>(e, px, py, pz, tx, ty, tz, lanes) != expected;
    }
    CHECK(differing == 0);
    CHECK(blocked > 1000);
    CHECK(open > 1000);
}

TEST(blocked_lanes_answer_as_each_lane_alone) {
    check_blocked_lanes<double>(31);
    check_blocked_lanes<float>(32);
}
