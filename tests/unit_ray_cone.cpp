// RayCone rules a sphere out for a packet only where no ray of the packet meets it:
// for packets from tight to nearly 90 degrees wide, single rays among them, every
// sphere that misses() rules out is checked in long double against every ray, and
// spheres that a ray grazes from inside (at 1 - 1e-12 of the radius) must never be
// ruled out. The cone must also rule out a good share, and be unusable for packets
// wider than 90 degrees or with a number that is not finite.
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

#include "check.h"
#include "random_checks.h"
#include "raytracer/flat_sweep/ray_cone.h"

namespace {

constexpr int N = 8;
using Cone = rt::RayCone<double>;
constexpr double kNoGuard = std::numeric_limits<double>::max();

struct Packet {
    double ox[N], oy[N], oz[N], dx[N], dy[N], dz[N];
};

// N rays around a random one: origins within `size`, directions within about `spread`
// radians, lengths from 0.3 to 3; `same` rays all equal to the first.
Packet random_packet(std::mt19937& g, double size, double spread, bool same) {
    Packet p{};
    const double bx = uniform(g, -6, 6), by = uniform(g, -6, 6), bz = uniform(g, -12, 2);
    double ux = uniform(g, -1, 1), uy = uniform(g, -1, 1), uz = uniform(g, -1, 1);
    const double length = std::sqrt(ux * ux + uy * uy + uz * uz);
    ux /= length, uy /= length, uz /= length;
    for (int k = 0; k < N; ++k) {
        const int from = same ? 0 : k;
        if (from != k) {
            p.ox[k] = p.ox[0], p.oy[k] = p.oy[0], p.oz[k] = p.oz[0];
            p.dx[k] = p.dx[0], p.dy[k] = p.dy[0], p.dz[k] = p.dz[0];
            continue;
        }
        p.ox[k] = bx + uniform(g, -size, size), p.oy[k] = by + uniform(g, -size, size);
        p.oz[k] = bz + uniform(g, -size, size);
        const double scale = uniform(g, 0.3, 3);
        p.dx[k] = (ux + uniform(g, -spread, spread)) * scale,
        p.dy[k] = (uy + uniform(g, -spread, spread)) * scale;
        p.dz[k] = (uz + uniform(g, -spread, spread)) * scale;
    }
    return p;
}

// Whether ray k meets the sphere (c, r) at some t > 0, in long double: its nearest
// approach to c over t >= 0 is within r.
bool meets(const Packet& p, int k, double cx, double cy, double cz, double r) {
    using L = long double;
    const L wx = L(cx) - p.ox[k], wy = L(cy) - p.oy[k], wz = L(cz) - p.oz[k];
    const L dx = p.dx[k], dy = p.dy[k], dz = p.dz[k];
    const L along = wx * dx + wy * dy + wz * dz, dd = dx * dx + dy * dy + dz * dz;
    const L t = along > 0 ? along / dd : L(0);
    const L ex = wx - t * dx, ey = wy - t * dy, ez = wz - t * dz;
    return ex * ex + ey * ey + ez * ez <= L(r) * L(r);
}

}  // namespace

TEST(ray_cone_rules_out_only_spheres_no_ray_meets) {
    std::mt19937 g(20261122);
    const double sizes[] = {0, 1e-3, 0.05, 0.5};
    const double spreads[] = {0, 1e-3, 0.05, 0.3, 0.6};
    long long wrong = 0, pairs = 0, ruled_out = 0, grazing = 0, grazing_out = 0, usable = 0;
    for (int round = 0; round < 20000; ++round) {
        const bool same = g() % 5 == 0;
        const Packet p = random_packet(g, sizes[g() % 4], spreads[g() % 5], same);
        const Cone cone = Cone::of<N>(p.ox, p.oy, p.oz, p.dx, p.dy, p.dz);
        if (!cone.usable) continue;
        ++usable;
        // Random spheres, of all sizes, anywhere.
        for (int s = 0; s < 20; ++s) {
            const double cx = uniform(g, -15, 15), cy = uniform(g, -15, 15), cz = uniform(g, -20, 10);
            const double r = std::exp(uniform(g, -6, 2));
            ++pairs;
            if (cone.misses(cx, cy, cz, r, kNoGuard) == 0) continue;
            ++ruled_out;
            for (int k = 0; k < N; ++k) wrong += meets(p, k, cx, cy, cz, r);
        }
        // A sphere that ray k passes through at 1 - 1e-12 of its radius from the centre.
        const int k = static_cast<int>(g() % N);
        const double t = uniform(g, 0.01, 5), r = std::exp(uniform(g, -6, 1));
        const double px = p.ox[k] + p.dx[k] * t, py = p.oy[k] + p.dy[k] * t, pz = p.oz[k] + p.dz[k] * t;
        // A unit vector across the ray.
        double wx = uniform(g, -1, 1), wy = uniform(g, -1, 1), wz = uniform(g, -1, 1);
        const double dd = p.dx[k] * p.dx[k] + p.dy[k] * p.dy[k] + p.dz[k] * p.dz[k];
        const double along = (wx * p.dx[k] + wy * p.dy[k] + wz * p.dz[k]) / dd;
        wx -= along * p.dx[k], wy -= along * p.dy[k], wz -= along * p.dz[k];
        const double length = std::sqrt(wx * wx + wy * wy + wz * wz);
        const double off = r * (1 - 1e-12) / length;
        const double cx = px + wx * off, cy = py + wy * off, cz = pz + wz * off;
        if (!meets(p, k, cx, cy, cz, r)) continue;  // rounding of the construction
        ++grazing;
        grazing_out += cone.misses(cx, cy, cz, r, kNoGuard) != 0;
    }
    CHECK(wrong == 0);
    CHECK(grazing_out == 0);
    CHECK(grazing > 10000);
    CHECK(usable > 10000);
    CHECK(ruled_out > pairs / 3);  // it pays
}

TEST(ray_cone_is_unusable_when_wide_or_not_finite) {
    std::mt19937 g(7);
    Packet p = random_packet(g, 0.1, 0.01, false);
    CHECK(Cone::of<N>(p.ox, p.oy, p.oz, p.dx, p.dy, p.dz).usable);
    // Two opposite directions: wider than 90 degrees.
    Packet wide = p;
    wide.dx[3] = -p.dx[0], wide.dy[3] = -p.dy[0], wide.dz[3] = -p.dz[0];
    CHECK(!Cone::of<N>(wide.ox, wide.oy, wide.oz, wide.dx, wide.dy, wide.dz).usable);
    const double nan = std::numeric_limits<double>::quiet_NaN(),
                 inf = std::numeric_limits<double>::infinity();
    for (const double bad : {nan, inf}) {
        Packet q = p;
        q.ox[5] = bad;
        CHECK(!Cone::of<N>(q.ox, q.oy, q.oz, q.dx, q.dy, q.dz).usable);
        q = p;
        q.dz[2] = bad;
        CHECK(!Cone::of<N>(q.ox, q.oy, q.oz, q.dx, q.dy, q.dz).usable);
        q = p;
        q.dx[N / 2] = 0, q.dy[N / 2] = 0, q.dz[N / 2] = 0;  // the axis ray has no direction
        CHECK(!Cone::of<N>(q.ox, q.oy, q.oz, q.dx, q.dy, q.dz).usable);
    }
    // Beyond the guard nothing is ruled out.
    const Cone cone = Cone::of<N>(p.ox, p.oy, p.oz, p.dx, p.dy, p.dz);
    const double cx = p.ox[0] - p.dx[0] * 5, cy = p.oy[0] - p.dy[0] * 5,
                 cz = p.oz[0] - p.dz[0] * 5;  // behind
    CHECK(cone.misses(cx, cy, cz, 0.1, kNoGuard) != 0);
    CHECK(cone.misses(cx, cy, cz, 0.1, 1.0) == 0);
}
