// The shading of up to kPacket ray hits on one ellipsoid, ray k in lane k of every
// array: shading.h's functions, the reference's own (whitted.h), run over the lanes a
// vector register at a time (Lanes of one register: kChunk lanes), so each lane gets its
// pixel's bits; the packet keeps the terms as arrays for the shadow tests
// (packet_shading.h).
//
// WHY: neighbouring pixels mostly see the same ellipsoid, and all of the shading
// arithmetic but the shadow rays is then the same chain of operations per pixel, run
// with the pixels as the lanes of vector instructions. A register at a time keeps each
// chain in registers (as the tree's tiles do too): shading.h over Lanes of all 16 lanes
// at once spills them, and measured 15-20% slower here (the course scenes and the heavy
// scene, one thread).
//
// Shadow rays are PacketTracer::lit_lanes()'s, and what each mirrored ray hits is
// PacketTracer::nearest_hits()'s (packet_shading.h).
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>

#include "raytracer/accel/exact_culling.h"
#include "raytracer/lanes.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/shading.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

// A packet's lanes: two vector registers of doubles, 16 with AVX-512, else 8, for the
// plain loops over lanes (the shading goes a register of kChunk lanes at a time).
// Measured (heavy 400x400, one thread, task-clock medians of 11 interleaved runs,
// AVX-512): 8 lanes 167.5 ms, 16 lanes 149.1 ms, 32 lanes 200.3 ms; the per-light work
// that does not depend on the lanes (the candidate loop, the tries' bookkeeping) is
// shared by twice the rays, while packets stay nearly as full.
#if defined(__AVX512F__)
inline constexpr int kPacket = 16;
#else
inline constexpr int kPacket = 8;
#endif
// Packets of up to kPacket / 4 rays are that wide: a packet costs its width in vector
// work whatever its count, and the mirrored rays of a packet split by the ellipsoid they
// hit. Heavy scene, counts of 1-4 rays: 2% of the eye packets, 14%, 30% and 44% of those
// after the first, second and third bounce. A third width, kPacket / 2, did not pay for
// its code (heavy 400x400, whole process, medians of 21: 36.6 ms with it, 36.2 without).
inline constexpr int kNarrowestPacket = kPacket / 4;

// Calls shade(std::integral_constant<int, width>) with the narrower packet width that
// holds count rays.
template <typename Shade>
void packet_width(int count, Shade shade) {
    if (count <= kNarrowestPacket)
        shade(std::integral_constant<int, kNarrowestPacket>{});
    else
        shade(std::integral_constant<int, kPacket>{});
}

// The terms of one light for the lanes of a HitPacket (light_ray(): HitPacket::light()).
template <typename Real, int Width = kPacket>
struct LightLanes {
    static constexpr int N = Width;
    Real tx[N], ty[N], tz[N];  // L - P
    Real distance[N];          // |L - P|
    Real lx[N], ly[N], lz[N];  // normalize(L - P)
    Real n_dot_l[N];
    // Lane sets, bit k for lane k (lanes from count on repeat the last ray).
    std::uint64_t front = 0;  // N.L > 0
    std::uint64_t lit = 0;    // in front and not in shadow: the light adds its terms
};

template <typename Real, int Width = kPacket>
struct HitPacket {
    static constexpr int N = Width;
    static constexpr int kChunk = kRegisterLanes<Real, N>;
    static_assert(N % kChunk == 0, "whole registers");
    using Q = Lanes<Real, kChunk>;
    using Lights = LightLanes<Real, Width>;
    int count = 0;
    Real ox[N], oy[N], oz[N];        // the ray's origin
    Real dx[N], dy[N], dz[N], t[N];  // its direction and root
    LaneBits inside = 0;             // the far root was taken
    Real px[N], py[N], pz[N];        // surface_point(): the point,
    Real nx[N], ny[N], nz[N];        // the unit normal facing the viewer,
    Real vx[N], vy[N], vz[N];        // the way to the viewer,
    Real scaled_length[N];           // and |(P - C) / s^2|
    Real abs_c[N];                   // own_abs_c(), for leaves_own_ellipsoid()
    Real r[N], g[N], b[N];           // the colour

    // The rays; lanes from count on repeat the last ray (their results are not used).
    void load(int n, const Real* from_x, const Real* from_y, const Real* from_z, const Real* x, const Real* y,
              const Real* z, const Real* root, const bool* in) {
        count = n;
        inside = 0;
        for (int k = 0; k < N; ++k) {
            const int from = k < n ? k : n - 1;
            ox[k] = from_x[from], oy[k] = from_y[from], oz[k] = from_z[from];
            dx[k] = x[from], dy[k] = y[from], dz[k] = z[from], t[k] = root[from];
            inside |= in[from] ? kLaneBits<N>.bit[k] : 0;
        }
    }

    // surface_point() on ellipsoid e without the way to the viewer, and the colour its
    // ambient term: all that a packet needs where no light faces any lane (a light
    // behind the ellipsoid, as in testImgPlane), or for its mirrored rays.
    void surface(const Ellipsoid<Real>& e, const Vec3<Real>& ambient) {
        const Vec3<Q> centre = Vec3<Q>::from(e.centre), scale_squared = Vec3<Q>::from(e.scale_squared);
        for (int c = 0; c < N; c += kChunk) {
            const SurfacePoint<Q> s =
                surface_point(chunk(ox, oy, oz, c), chunk(dx, dy, dz, c), Q::load(t + c),
                              lanes_from<kChunk>(inside, c), centre, scale_squared);
            store(s.point, px, py, pz, c), store(s.normal, nx, ny, nz, c);
            store(s.scaled_length, scaled_length, c);
        }
        for (int k = 0; k < N; ++k) r[k] = ambient.x, g[k] = ambient.y, b[k] = ambient.z;
    }

    // What the lights' terms need besides: |c| for the self-shadow test (as the tree's
    // tiles compute it), and the way to the viewer (surface_point()'s) where a specular
    // term may show. Once a packet, when the first light faces some lane.
    void facing_light(const Ellipsoid<Real>& e) {
        const Vec3<Q> centre = Vec3<Q>::from(e.centre), scale = Vec3<Q>::from(e.scale);
        const bool viewer = !specular_is_zero(e);
        for (int c = 0; c < N; c += kChunk) {
            if (viewer) store(normalize(-chunk(dx, dy, dz, c)), vx, vy, vz, c);
            store(own_abs_c(chunk(px, py, pz, c), centre, scale), abs_c, c);
        }
    }

    // light_ray() to the light at position; lit starts empty. False when no lane has
    // the light in front.
    bool light(const Vec3<Real>& position, Lights& l) const {
        const Vec3<Q> at = Vec3<Q>::from(position);
        l.front = 0, l.lit = 0;
        for (int c = 0; c < N; c += kChunk) {
            const LightRay<Q> ray = light_ray(surface_chunk(c, false), at);
            store(ray.to_light, l.tx, l.ty, l.tz, c), store(ray.l, l.lx, l.ly, l.lz, c);
            store(ray.distance, l.distance, c), store(ray.n_dot_l, l.n_dot_l, c);
            l.front |= LaneBits(ray.faces) << c;
        }
        return l.front != 0;
    }

    // The lanes where the own ellipsoid cannot block the shadow ray to light l
    // (leaves_own_ellipsoid(), exact_culling.h), seen from outside.
    LaneBits self_clear(const Lights& l) const {
        LaneBits set = 0;
        for (int c = 0; c < N; c += kChunk)
            set |= LaneBits(leaves_own_ellipsoid<Real>(Q::load(scaled_length + c), Q::load(l.distance + c),
                                                       Q::load(l.n_dot_l + c), Q::load(abs_c + c)))
                   << c;
        return set & ~inside;
    }

    // add_light() for light l, of this intensity, where l.lit.
    void add_light(const Lights& l, const Vec3<Real>& intensity, const Finish<Q>& finish) {
        const Vec3<Q> from = Vec3<Q>::from(intensity);
        for (int c = 0; c < N; c += kChunk) {
            const LaneBits lit = lanes_from<kChunk>(l.lit, c);
            if (lit == 0) continue;
            LightRay<Q> ray;
            ray.l = chunk(l.lx, l.ly, l.lz, c), ray.n_dot_l = Q::load(l.n_dot_l + c);
            Vec3<Q> colour = chunk(r, g, b, c);
            rt::add_light(colour, surface_chunk(c, finish.specular != 0), ray, from, finish, lit);
            store(colour, r, g, b, c);
        }
    }

    // mirrored(): each lane's direction off its normal, into (x, y, z).
    void mirror(Real* x, Real* y, Real* z) const {
        for (int c = 0; c < N; c += kChunk)
            store(mirrored(chunk(nx, ny, nz, c), chunk(dx, dy, dz, c)), x, y, z, c);
    }

    // Whitted::shade(): colour += seen * kr, for lane k.
    void add(int k, const Vec3<Real>& term) { r[k] += term.x, g[k] += term.y, b[k] += term.z; }

private:
    static Vec3<Q> chunk(const Real* x, const Real* y, const Real* z, int c) {
        return {Q::load(x + c), Q::load(y + c), Q::load(z + c)};
    }
    static void store(const Q& q, Real* to, int c) { std::memcpy(to + c, q.data(), sizeof(Real) * kChunk); }
    static void store(const Vec3<Q>& v, Real* x, Real* y, Real* z, int c) {
        store(v.x, x, c), store(v.y, y, c), store(v.z, z, c);
    }
    // The surface of lanes [c, c + kChunk), its way to the viewer only where asked (and
    // computed: facing_light()).
    SurfacePoint<Q> surface_chunk(int c, bool viewer) const {
        SurfacePoint<Q> s;
        s.point = chunk(px, py, pz, c), s.normal = chunk(nx, ny, nz, c);
        s.scaled_length = Q::load(scaled_length + c);
        if (viewer) s.to_viewer = chunk(vx, vy, vz, c);
        return s;
    }
};

}  // namespace rt
