// The shading arithmetic of up to kPacket ray hits on one ellipsoid, ray k in lane k of
// every array: the point, its normal, and per light L - P, N.L, R.V, the specular power
// and the colour sums (SPEC section 5), and the mirrored directions.
//
// WHY: the reference (shading.h, for one ray in whitted.h) is a chain of dependent
// products, square roots and divisions with branches in between. Neighbouring pixels
// mostly see the same ellipsoid, so here the same chain runs over the pixels as flat
// loops over fixed-size arrays, which GCC and Clang turn into vector instructions (8
// doubles per AVX-512 instruction). Each lane performs exactly shading.h's operations
// in its order (named at each step), lanes do not mix, and vector instructions round as
// scalar ones do (no fused multiply-adds: CMakeLists.txt), so each pixel gets the same
// bits. Where the reference skips a term (light behind, in shadow, R.V <= 0), the lane
// keeps its sum by a select; no zero is added.
//
// Shadow rays are Tracer::shadow_lanes()'s (or one at a time, Tracer::hit_colours()),
// and what each mirrored ray hits is Tracer::nearest_hits()'s (packet_shading.h).
//
// shading.h over Lanes (lanes.h), as the tree's tiles run it, measured 20-30% slower
// here on the heavy scene (one thread): each Lanes operation is a loop of its own,
// stored and loaded, where these loops keep a chain in registers.
//
// The loops with selects or a variable trip count around them (the sums, the whole
// power, R.V) are marked RT_VECTOR_LOOP: GCC unrolled them completely first and then
// left them as 8 scalar lanes with a branch each (measured: heavy 100x100 139.2 ->
// 112.9 M instructions once vectorised).
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "raytracer/compiler.h"
#include "raytracer/lanes.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

// Two vector registers of doubles per operation: 16 lanes with AVX-512, else 8.
// Measured (heavy 400x400, one thread, task-clock medians of 11 interleaved runs,
// AVX-512): 8 lanes 167.5 ms, 16 lanes 149.1 ms, 32 lanes 200.3 ms; the per-light work
// that does not depend on the lanes (the candidate loop, the tries' bookkeeping) is
// shared by twice the rays, while packets stay nearly as full.
#if defined(__AVX512F__)
inline constexpr int kPacket = 16;
#else
inline constexpr int kPacket = 8;
#endif
// Packets are also kPacket / 2 and kPacket / 4 lanes wide, for fewer rays: a packet
// costs its width in vector work whatever its count, and the mirrored rays of a packet
// split by the ellipsoid they hit. Heavy scene, counts of 1-4 rays: 2% of the eye
// packets, 14%, 30% and 44% of those after the first, second and third bounce.
inline constexpr int kNarrowestPacket = kPacket / 4;

// Calls shade(std::integral_constant<int, width>) with the narrowest packet width that
// holds count rays.
template <typename Shade>
void packet_width(int count, Shade shade) {
    if (count <= kNarrowestPacket)
        shade(std::integral_constant<int, kNarrowestPacket>{});
    else if (count <= kPacket / 2)
        shade(std::integral_constant<int, kPacket / 2>{});
    else
        shade(std::integral_constant<int, kPacket>{});
}

// The terms of one light for the lanes of a HitPacket (HitPacket::light()).
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
    using Lanes = LightLanes<Real, Width>;
    int count = 0;
    Real ox[N], oy[N], oz[N];        // the ray's origin
    Real dx[N], dy[N], dz[N], t[N];  // its direction and root
    Real inside[N];                  // masks are 1 or 0 (bool arrays would keep loops scalar)
    Real px[N], py[N], pz[N];        // the hit point
    Real cx[N], cy[N], cz[N];        // point - centre
    Real nx[N], ny[N], nz[N];        // the unit normal, facing the viewer
    Real scaled_length[N];           // |(P - C) / s^2|
    Real self_c[N];                  // |o'.o' - 1| of the self-shadow test
    Real self_test[N];               // mask
    Real vx[N], vy[N], vz[N];        // normalize(-direction)
    Real r[N], g[N], b[N];           // the colour

    // The rays; lanes from count on repeat the last ray (their results are not used).
    void load(int n, const Real* from_x, const Real* from_y, const Real* from_z, const Real* x, const Real* y,
              const Real* z, const Real* root, const bool* in) {
        count = n;
        for (int k = 0; k < N; ++k) {
            const int from = k < n ? k : n - 1;
            ox[k] = from_x[from], oy[k] = from_y[from], oz[k] = from_z[from];
            dx[k] = x[from], dy[k] = y[from], dz[k] = z[from], t[k] = root[from], inside[k] = mask(in[from]);
        }
    }

    // surface_point(): point = origin + direction * t; to_centre = point -
    // centre; scaled = to_centre / s^2; scaled_length = length(scaled); normal = scaled *
    // (1 / scaled_length), negated when inside.
    void surface(const Vec3<Real>& centre, const Vec3<Real>& scale_squared) {
        using std::sqrt;
        for (int k = 0; k < N; ++k) {
            px[k] = ox[k] + dx[k] * t[k], py[k] = oy[k] + dy[k] * t[k], pz[k] = oz[k] + dz[k] * t[k];
            cx[k] = px[k] - centre.x, cy[k] = py[k] - centre.y, cz[k] = pz[k] - centre.z;
            const Real sx = cx[k] / scale_squared.x, sy = cy[k] / scale_squared.y,
                       sz = cz[k] / scale_squared.z;
            const Real length = sqrt(sx * sx + sy * sy + sz * sz);
            scaled_length[k] = length;
            const Real inverse = Real(1) / length;
            const Real ux = sx * inverse, uy = sy * inverse, uz = sz * inverse;
            const bool flip = inside[k] != 0;
            nx[k] = flip ? -ux : ux, ny[k] = flip ? -uy : uy, nz[k] = flip ? -uz : uz;
        }
    }

    void start_colour(const Vec3<Real>& ambient) {
        for (int k = 0; k < N; ++k) r[k] = ambient.x, g[k] = ambient.y, b[k] = ambient.z;
    }

    // self_clear()'s terms: o = to_centre / scale; self_c = |o.o - 1| (as intersect()
    // computes it); the test holds outside and where self_c is a number.
    void self_terms(const Vec3<Real>& scale) {
        using std::abs;
        for (int k = 0; k < N; ++k) {
            const Real ox = cx[k] / scale.x, oy = cy[k] / scale.y, oz = cz[k] / scale.z;
            self_c[k] = abs(ox * ox + oy * oy + oz * oz - Real(1));
            self_test[k] = (Real(1) - inside[k]) * mask(self_c[k] == self_c[k]);
        }
    }

    // surface_point(): to_viewer = normalize(-direction).
    void viewer() {
        using std::sqrt;
        for (int k = 0; k < N; ++k) {
            const Real x = -dx[k], y = -dy[k], z = -dz[k];
            const Real inverse = Real(1) / sqrt(x * x + y * y + z * z);
            vx[k] = x * inverse, vy[k] = y * inverse, vz[k] = z * inverse;
        }
    }

    // light_ray(): to_light = L - P; light_distance = length(to_light); l =
    // to_light * (1 / light_distance); n_dot_l = dot(normal, l); front when n_dot_l > 0.
    // lit starts empty. False when no pixel has the light in front.
    bool light(const Vec3<Real>& position, Lanes& l) const {
        using std::sqrt;
        Real* const tx = l.tx;
        Real* const ty = l.ty;
        Real* const tz = l.tz;
        Real* const distance = l.distance;
        Real* const lx = l.lx;
        Real* const ly = l.ly;
        Real* const lz = l.lz;
        Real* const n_dot_l = l.n_dot_l;
        Real front[N];
        for (int k = 0; k < N; ++k) {
            const Real x = position.x - px[k], y = position.y - py[k], z = position.z - pz[k];
            const Real d = sqrt(x * x + y * y + z * z);
            const Real inverse = Real(1) / d;
            const Real ux = x * inverse, uy = y * inverse, uz = z * inverse;
            const Real cosine = nx[k] * ux + ny[k] * uy + nz[k] * uz;
            tx[k] = x, ty[k] = y, tz[k] = z, distance[k] = d, lx[k] = ux, ly[k] = uy, lz[k] = uz;
            n_dot_l[k] = cosine;
            front[k] = mask(cosine > 0);
        }
        // Lanes from count on repeat the last ray, so all N lanes can be asked (a fixed
        // vector loop instead of a scalar one over count).
        l.front = bits(front);
        l.lit = 0;
        return l.front != 0;
    }

    // The lanes where the own ellipsoid cannot block the shadow ray to light l
    // (leaves_own_ellipsoid(), spec_rules.h). Only asked where the own ellipsoid is a
    // candidate.
    std::uint64_t self_clear(const Lanes& l) const {
        std::uint64_t set = 0;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) {
            const Real clear = self_test[k] * mask(leaves_own_ellipsoid<Real>(scaled_length[k], l.distance[k],
                                                                              l.n_dot_l[k], self_c[k]));
            set |= clear != 0 ? kLaneBit[k] : 0;
        }
        return set;
    }

    // add_light(): colour += (Ip Kd * n_dot_l) * O where lit.
    void add_diffuse(const Lanes& l, const Vec3<Real>& diffuse, const Vec3<Real>& colour) {
        const Real* const n_dot_l = l.n_dot_l;
        const std::uint64_t lit = l.lit;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) {
            const Real dr = r[k] + (diffuse.x * n_dot_l[k]) * colour.x;
            const Real dg = g[k] + (diffuse.y * n_dot_l[k]) * colour.y;
            const Real db = b[k] + (diffuse.z * n_dot_l[k]) * colour.z;
            const bool adds = (lit & kLaneBit[k]) != 0;
            r[k] = adds ? dr : r[k], g[k] = adds ? dg : g[k], b[k] = adds ? db : b[k];
        }
    }

    // add_light(): reflected = normal * (2 * n_dot_l) - l; r_dot_v = dot(reflected,
    // to_viewer); colour += Ip Ks * r_dot_v^n where lit and r_dot_v > 0, the power by
    // whole_power() (power.h), the same multiplications in each lane.
    void specular_whole(const Lanes& l, const Vec3<Real>& specular, std::int32_t exponent) {
        Real r_dot_v[N], result[N], base[N];
        reflect(l, r_dot_v);
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) result[k] = 1, base[k] = r_dot_v[k];
        for (std::int32_t bits = exponent; bits != 0; bits >>= 1) {
            if (bits & 1) {
                RT_VECTOR_LOOP
                for (int k = 0; k < N; ++k) result[k] *= base[k];
            }
            RT_VECTOR_LOOP
            for (Real& x : base) x *= x;
        }
        add_specular(l.lit, specular, r_dot_v, result);
    }

    // The same with std::pow for an exponent that is not a whole number.
    void specular_pow(const Lanes& l, const Vec3<Real>& specular, Real exponent) {
        using std::pow;
        Real r_dot_v[N], result[N];
        reflect(l, r_dot_v);
        for (int k = 0; k < N; ++k)
            result[k] = (l.lit & kLaneBit[k]) != 0 && r_dot_v[k] > 0 ? pow(r_dot_v[k], exponent) : Real(0);
        add_specular(l.lit, specular, r_dot_v, result);
    }

    // mirrored(): direction - normal * (2 * dot(normal, direction)).
    void mirror(Real* x, Real* y, Real* z) const {
        for (int k = 0; k < N; ++k) {
            const Real twice = 2 * (nx[k] * dx[k] + ny[k] * dy[k] + nz[k] * dz[k]);
            x[k] = dx[k] - nx[k] * twice, y[k] = dy[k] - ny[k] * twice, z[k] = dz[k] - nz[k] * twice;
        }
    }

    // Lane masks as bit sets, bit k for lane k (64-bit like the lanes of doubles, and
    // selects of constant bits rather than shifts by k, so that GCC vectorises these).
    static constexpr const std::uint64_t (&kLaneBit)[N] = kLaneBits<N>.bit;
    static std::uint64_t bits(const Real* mask) {
        std::uint64_t set = 0;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) set |= mask[k] != 0 ? kLaneBit[k] : 0;
        return set;
    }

    // Whitted::shade(): colour += seen * kr, for lane k.
    void add(int k, const Vec3<Real>& term) { r[k] += term.x, g[k] += term.y, b[k] += term.z; }

private:
    static Real mask(bool b) { return b ? Real(1) : Real(0); }

    void reflect(const Lanes& l, Real* r_dot_v) const {
        const Real* const n_dot_l = l.n_dot_l;
        const Real* const lx = l.lx;
        const Real* const ly = l.ly;
        const Real* const lz = l.lz;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) {
            const Real twice = 2 * n_dot_l[k];
            const Real rx = nx[k] * twice - lx[k], ry = ny[k] * twice - ly[k], rz = nz[k] * twice - lz[k];
            r_dot_v[k] = rx * vx[k] + ry * vy[k] + rz * vz[k];
        }
    }

    void add_specular(std::uint64_t lit, const Vec3<Real>& specular, const Real* r_dot_v, const Real* power) {
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) {
            const bool adds =
                mask((lit & kLaneBit[k]) != 0) * mask(r_dot_v[k] > 0) != 0;  // no &&: it would branch
            const Real sr = r[k] + specular.x * power[k];
            const Real sg = g[k] + specular.y * power[k];
            const Real sb = b[k] + specular.z * power[k];
            r[k] = adds ? sr : r[k], g[k] = adds ? sg : g[k], b[k] = adds ? sb : b[k];
        }
    }
};

}  // namespace rt
