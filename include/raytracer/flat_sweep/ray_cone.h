// A cone holding every ray of a packet: a ball around the origins and a cone of
// directions. SphereBounds::candidate_lanes() rules out with it, once per packet, the
// bounding spheres that no ray of the packet can meet, before its test per ray.
//
// WHY: the mirrored rays of a packet leave neighbouring points in nearby directions,
// and most spheres lie far off all of them (heavy scene: 14% of sphere-packet pairs
// have a ray that may meet the sphere). The test per ray costs about 25 operations per
// ray and sphere; this one costs about as much per sphere for the whole packet.
//
// The test: a ray p + t u (t > 0, |p - o| <= r0) meets the sphere (c, r) only if the ray
// o + t u meets the sphere (c, R = r + r0) (move both by o - p). Seen from o outside it,
// that sphere spans the directions within beta = asin(R / |w|) of w = c - o; the
// directions lie within s of the axis a; so no ray meets it when the angle between a and
// w exceeds beta + s, i.e. when a.w < |w| cos(beta + s) = sqrt(|w|^2 - R^2) cos s - R sin s
// (a cone-sphere test, here without square root or division: squared where both sides
// are positive; LightCones::packet() makes one of the same kind, its apex at a light).
//
// Rounding: the spheres are SphereBounds's, inflated far beyond intersect()'s rounding;
// this test only has to be conservative in exact arithmetic for them. Its own errors
// are a few ulps of |w|, which SphereBounds's guard keeps within 1e6 smallest scales:
// at most ~1e-9 R, against margins of 1e-6 R on the radius and 1e-9 on the cosine and
// sine of the spread (tests/unit_ray_cone.cpp checks every culled pair in long double).
#pragma once

#include <cmath>

namespace rt {

template <typename C>
struct RayCone {
    C x = 0, y = 0, z = 0, radius = 0;  // the ball around the origins
    C ax = 0, ay = 0, az = 0;           // the unit axis
    C cos_spread = 0, sin_spread = 1;   // every direction is within this angle of the axis
    bool usable = false;                // false: not worth it (a wide cone) or not finite

    static constexpr double kRadiusMargin = 1e-6;  // relative, on the sphere's radius
    static constexpr double kAngleMargin = 1e-9;   // on cos and sin of the spread

    // The cone of N rays, ray k from (ox, oy, oz)[k] along (dx, dy, dz)[k]: around the
    // middle ray's origin and direction (any ray of the packet serves as the centre, and
    // no sum or box over the rays is needed, which would not vectorise).
    template <int N, typename Real>
    static RayCone of(const Real* ox, const Real* oy, const Real* oz, const Real* dx, const Real* dy,
                      const Real* dz) {
        using std::sqrt;
        constexpr int kMiddle = N / 2;
        RayCone cone;
        cone.x = C(ox[kMiddle]), cone.y = C(oy[kMiddle]), cone.z = C(oz[kMiddle]);
        {
            const C vx = C(dx[kMiddle]), vy = C(dy[kMiddle]), vz = C(dz[kMiddle]);
            const C inverse = C(1) / sqrt(vx * vx + vy * vy + vz * vz);
            cone.ax = vx * inverse, cone.ay = vy * inverse, cone.az = vz * inverse;
        }
        C distance2[N], cosine[N];
        for (int k = 0; k < N; ++k) {
            const C px = C(ox[k]) - cone.x, py = C(oy[k]) - cone.y, pz = C(oz[k]) - cone.z;
            distance2[k] = px * px + py * py + pz * pz;
            const C vx = C(dx[k]), vy = C(dy[k]), vz = C(dz[k]);
            const C inverse = C(1) / sqrt(vx * vx + vy * vy + vz * vz);
            cosine[k] = (cone.ax * vx + cone.ay * vy + cone.az * vz) * inverse;
        }
        C farthest2 = 0, least = 1;  // a NaN is kept: it makes the cone unusable below
        for (int k = 0; k < N; ++k) {
            farthest2 = distance2[k] > farthest2 || distance2[k] != distance2[k] ? distance2[k] : farthest2;
            least = cosine[k] < least || cosine[k] != cosine[k] ? cosine[k] : least;
        }
        cone.radius = sqrt(farthest2) * (C(1) + C(kRadiusMargin));
        cone.cos_spread = least - C(kAngleMargin);
        cone.sin_spread = sqrt(C(1) - cone.cos_spread * cone.cos_spread) + C(kAngleMargin);
        // Every number finite (x - x is 0, else NaN), and the spread under 90 degrees
        // (cos > 0; a NaN fails): the test below assumes both.
        const C finite = (cone.x - cone.x) + (cone.y - cone.y) + (cone.z - cone.z) +
                         (cone.radius - cone.radius) + (cone.ax - cone.ax) + (cone.ay - cone.ay) +
                         (cone.az - cone.az) + (cone.sin_spread - cone.sin_spread);
        cone.usable = finite == 0 && cone.cos_spread > 0;
        return cone;
    }

    // 1 where no ray of the cone meets the sphere (centre (cx, cy, cz), radius r) at
    // t > 0, else 0; guard2: the squared distance from the centre beyond which nothing
    // is ruled out (SphereBounds's guard). A number, not a bool, for vector loops.
    C misses(C cx, C cy, C cz, C r, C guard2) const {
        const C big_r = r * (C(1) + C(kRadiusMargin)) + radius;
        const C wx = cx - x, wy = cy - y, wz = cz - z;
        const C w2 = wx * wx + wy * wy + wz * wz;
        const C q = ax * wx + ay * wy + az * wz + big_r * sin_spread;
        const C rest = w2 - big_r * big_r;  // |w|^2 - R^2: positive when o is outside
        // Every origin within the guard: |w| + radius <= sqrt(guard2).
        const C guarded =
            (C(4) * w2 <= guard2 ? C(1) : C(0)) * (C(4) * radius * radius <= guard2 ? C(1) : C(0));
        const C beyond = (q < 0 ? C(1) : C(0)) + (q * q < rest * cos_spread * cos_spread ? C(1) : C(0));
        return guarded * (rest > 0 ? C(1) : C(0)) * (beyond != 0 ? C(1) : C(0));
    }
};

}  // namespace rt
