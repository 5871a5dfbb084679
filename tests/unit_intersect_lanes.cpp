// The nearest hits of a packet's mirrored rays found for all lanes at once
// (PacketTracer::nearest_hits(), with intersect_lanes() and SphereBounds::candidate_lanes())
// against the reference's search, one ray against every ellipsoid (BruteForce::closest()):
// intersect_lanes() must give every lane intersect()'s roots bit for bit, in float,
// double and long double, and nearest_hits() every lane the reference's ellipsoid, root
// (bit for bit) and inside flag, in the flat sweep's double and long double; for
// random rays, rays from points on the surfaces (as reflected rays start), rays near
// tangency (the allowance of intersect_mapped()) and grazing rays from the surface
// (q == 0), where a lane that rounds or compares differently would show.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/accel/intersect_lanes.h"
#include "raytracer/flat_sweep/packet_tracer.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene.h"

namespace {

constexpr int N = rt::kPacket;

// Equal values with equal signs (0 and -0 differ), or both NaN.
template <typename Real>
bool same(Real a, Real b) {
    return (a == b && std::signbit(a) == std::signbit(b)) || (a != a && b != b);
}

rt::SphereSpec random_sphere(std::mt19937& g, int i) {
    rt::SphereSpec s{};
    s.centre = {uniform(g, -5, 5), uniform(g, -5, 5), uniform(g, -10, 0)};
    s.scale = {uniform(g, 0.1, 4), uniform(g, 0.1, 4), uniform(g, 0.1, 4)};
    if (i % 3 == 1) s.scale.y = -s.scale.y;  // negated scales are legal
    if (i % 7 == 3) s.scale.z = 0.001;       // a thin disc
    if (i % 5 == 2) s.scale = {20, 15, 25};  // a room around the others
    s.colour = {0.5, 0.5, 0.5};
    s.ka = 0.2, s.kd = 0.5, s.ks = 0.5, s.kr = 0.5, s.shininess = 20;
    return s;
}

template <typename Real>
struct Ray {
    rt::Vec3<Real> origin, direction;
};

// A ray for ellipsoid e: from a random point, from its surface, near-tangent (the mapped
// line's distance from the centre within a few ulps of 1), or grazing from the surface.
template <typename Real>
Ray<Real> random_ray(std::mt19937& g, const rt::Ellipsoid<Real>& e) {
    using V = rt::Vec3<Real>;
    auto unit = [&]() {
        const V u{Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1))};
        using std::sqrt;
        return u * (Real(1) / sqrt(dot(u, u)));
    };
    const V direction{Real(uniform(g, -9, 9)), Real(uniform(g, -9, 9)), Real(uniform(g, -9, 9))};
    switch (g() % 5) {
        case 0:
            return {V{Real(uniform(g, -30, 30)), Real(uniform(g, -30, 30)), Real(uniform(g, -30, 30))},
                    direction};
        case 1:
            return {e.centre + unit() * e.scale, direction};  // on the surface (rounded)
        case 2: {
            // Tangent in the unit space: origin o, direction w perpendicular to the point
            // u of the sphere, moved off by a relative h of a few ulps either way.
            const V u = unit();
            V w = unit();
            w = w - u * dot(w, u);
            const Real h = Real(uniform(g, -8, 8)) * std::numeric_limits<Real>::epsilon();
            const V o = u * (Real(1) + h) - w * Real(uniform(g, 0.5, 30));
            return {e.centre + o * e.scale, (w * Real(uniform(g, 0.1, 3))) * e.scale};
        }
        case 3: {
            // Grazing from the surface: o on the axis, d along another axis (b = 0).
            const int axis = static_cast<int>(g() % 3);
            V o{}, d{};
            (axis == 0 ? o.x : axis == 1 ? o.y : o.z) = g() % 2 ? Real(1) : Real(-1);
            (axis == 0 ? d.y : axis == 1 ? d.z : d.x) = Real(uniform(g, -3, 3));
            return {e.centre + o * e.scale, d * e.scale};
        }
        default:
            return {e.centre + unit() * (e.scale * Real(uniform(g, 0.2, 3))), direction};
    }
}

template <typename Real>
long long differing_roots(unsigned seed, long long& hits, long long& grazing) {
    std::mt19937 g(seed);
    long long differing = 0;
    for (int round = 0; round < 4000; ++round) {
        const rt::Ellipsoid<Real> e = rt::make_ellipsoid<Real>(random_sphere(g, round));
        Real ox[N], oy[N], oz[N], dx[N], dy[N], dz[N], hit[N], near[N], far[N];
        Ray<Real> rays[N];
        for (int k = 0; k < N; ++k) {
            rays[k] = random_ray(g, e);
            ox[k] = rays[k].origin.x, oy[k] = rays[k].origin.y, oz[k] = rays[k].origin.z;
            dx[k] = rays[k].direction.x, dy[k] = rays[k].direction.y, dz[k] = rays[k].direction.z;
        }
        rt::intersect_lanes<N>(e, ox, oy, oz, dx, dy, dz, hit, near, far);
        for (int k = 0; k < N; ++k) {
            const rt::Roots<Real> r = rt::intersect(e, rays[k].origin, rays[k].direction);
            hits += r.hit != 0 ? 1 : 0;
            grazing += r.hit != 0 && r.near == 0 && r.far == 0;
            differing += (hit[k] != 0) != (r.hit != 0) ||
                         (r.hit != 0 && (!same(near[k], r.near) || !same(far[k], r.far)));
        }
    }
    return differing;
}

template <typename Real>
void roots_match() {
    long long hits = 0, grazing = 0;
    CHECK(differing_roots<Real>(11, hits, grazing) == 0);
    const long long rays = 4000LL * N;
    CHECK(hits > rays / 3);  // many rays hit, and some miss
    CHECK(hits < rays);
    CHECK(grazing > rays / 300);  // q == 0
}

// A scene of random ellipsoids (a room among them) and lights, and rays from points on
// their surfaces: every lane's nearest hit as the reference finds it.
template <typename Real>
long long differing_hits(unsigned seed, long long& found, long long& inside) {
    std::mt19937 g(seed);
    rt::Scene scene;
    scene.columns = 400, scene.rows = 400;
    for (int i = 0; i < 3 + static_cast<int>(seed % 12); ++i) scene.spheres.push_back(random_sphere(g, i));
    rt::LightSpec light{};
    light.position = {0, 0, -3}, light.intensity = {1, 1, 1};
    scene.lights.push_back(light);
    const rt::PacketTracer<Real> tracer(scene);
    rt::TraceScratch<Real> scratch = tracer.make_scratch();
    const rt::BruteForce<Real> reference(rt::make_ellipsoids<Real>(scene));
    long long differing = 0;
    for (int round = 0; round < 1500; ++round) {
        Real ox[N], oy[N], oz[N], dx[N], dy[N], dz[N], t[N];
        std::uint32_t index[N];
        bool in[N];
        Ray<Real> rays[N];
        const std::size_t count = scene.spheres.size();
        // Half the packets coherent (RayCone then rules spheres out for all lanes), half
        // of unrelated rays.
        const bool coherent = round % 2 == 0;
        for (int k = 0; k < N; ++k) {
            const rt::Ellipsoid<Real>& e = tracer.ellipsoid(g() % count);
            rays[k] = random_ray(g, e);
            if (g() % 2) {  // from a hit point, as a reflected ray starts
                const auto hit = reference.closest(rays[k].origin, rays[k].direction, rt::kEyeRayMinT);
                if (hit.found()) {
                    rays[k].origin = rays[k].origin + rays[k].direction * hit.t;
                    rays[k].direction = {Real(uniform(g, -9, 9)), Real(uniform(g, -9, 9)),
                                         Real(uniform(g, -9, 9))};
                }
            }
            if (coherent && k > 0) {  // near ray 0, as a packet's mirrored rays are
                const rt::Vec3<Real> offset{Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1)),
                                            Real(uniform(g, -1, 1))};
                const rt::Vec3<Real> turn{Real(uniform(g, -1, 1)), Real(uniform(g, -1, 1)),
                                          Real(uniform(g, -1, 1))};
                using std::sqrt;
                const Real length = sqrt(dot(rays[0].direction, rays[0].direction));
                rays[k].origin = rays[0].origin + offset * Real(0.05);
                rays[k].direction = rays[0].direction + turn * (Real(0.05) * length);
            }
            ox[k] = rays[k].origin.x, oy[k] = rays[k].origin.y, oz[k] = rays[k].origin.z;
            dx[k] = rays[k].direction.x, dy[k] = rays[k].direction.y, dz[k] = rays[k].direction.z;
        }
        const Real min_t = Real(rt::kReflectedRayMinT);
        tracer.nearest_hits(ox, oy, oz, dx, dy, dz, min_t, scratch, index, t, in);
        for (int k = 0; k < N; ++k) {
            const auto hit = reference.closest(rays[k].origin, rays[k].direction, min_t);
            if (!hit.found()) {
                differing += index[k] != rt::kNoEllipsoid;
                continue;
            }
            ++found;
            inside += hit.inside;
            differing += index[k] != hit.ellipsoid || !same(t[k], hit.t) || in[k] != hit.inside;
        }
    }
    return differing;
}

template <typename Real>
void hits_match() {
    long long found = 0, inside = 0, differing = 0;
    for (unsigned seed = 1; seed <= 12; ++seed) differing += differing_hits<Real>(seed, found, inside);
    const long long rays = 12LL * 1500 * N;
    CHECK(differing == 0);
    CHECK(found > rays / 6);  // many rays hit something, some from inside
    CHECK(found < rays);
    CHECK(inside > rays / 150);
}

}  // namespace

TEST(lane_roots_are_intersect_roots) {
    roots_match<float>();
    roots_match<double>();
    roots_match<long double>();
}

TEST(lane_nearest_hits_are_the_references) {
    hits_match<double>();
    hits_match<long double>();
}
