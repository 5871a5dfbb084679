// Decides most shadow-ray tests without intersect()'s divisions, and defers to it
// only where its answer could be close.
//
// WHY: a shadow ray needs only yes/no, "some root in (0.001, 1)". Computing the roots
// in the unit sphere's space with products by reciprocal scales (instead of the exact
// quotients) gives them, as intersect() does, to within about 1e-6 when the origin is
// not far away (|o'| <= 100) and the ray not too short (|d'| >= 1e-2). Where the mapped
// line clearly misses (1 - |l|^2 < -1e-6) or clearly crosses (> 1e-3) and every root
// is at least 1e-4 from 0.001 and 1, intersect() must give the same answer (compared
// times a = |d'|^2, so without any division); everything else (tangent rays, roots near
// the limits, far or tiny rays) runs intersect(). Images stay bit-identical. Measured
// gain in docs/speed.md.
#pragma once

#include <cmath>
#include <limits>

#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

// The prefilter's answers for N rays, lane k in element k (masks are 1 or 0).
template <typename Real, int N>
struct PrefilterLanes {
    Real blocked[N], unsure[N];
};

// Whether ellipsoid e blocks the shadow ray point + t to_light, 0.001 < t < 1, for N rays
// at once, ray k from (px, py, pz)[k] along (tx, ty, tz)[k]: blocked[k] = 1 where it
// clearly does, unsure[k] = 1 where intersect() must decide (else 0). The roots' common
// factor 1/a is multiplied out (a > 0): a t = -b -+ sqrt(b^2 - a c) against a times each
// limit. With |o'|^2 <= 1e4 and a >= 1e-4, b^2 - a c is off by a few ulps of a |o'|^2, so
// h = (b^2 - a c) / a by under 1e-11 and the roots by under 1e-8: far inside the margins.
// The tests' branches are products of 0/1 masks (doubles: bool temporaries and && keep
// GCC's loops scalar), so the loop runs as vector instructions; a lane that a branch
// would have stopped computes values (even NaN from a negative sqrt) that no mask takes.
template <int N, typename Real>
PrefilterLanes<Real, N> prefilter_shadow_lanes(const Ellipsoid<Real>& e, const Real* px, const Real* py,
                                               const Real* pz, const Real* tx, const Real* ty,
                                               const Real* tz) {
    // float's own rounding (1e-7 relative) is too close to the margins below.
    static_assert(std::numeric_limits<Real>::digits >= std::numeric_limits<double>::digits,
                  "the prefilter needs double or wider");
    using C = Real;
    auto mask = [](bool b) { return b ? C(1) : C(0); };
    PrefilterLanes<Real, N> out;
    using std::sqrt;
    const Vec3<C> centre = e.centre, inverse{C(1) / e.scale.x, C(1) / e.scale.y, C(1) / e.scale.z};
    const C lo = C(kShadowRayMinT), margin = C(1e-4);
    for (int k = 0; k < N; ++k) {
        const C ox = (px[k] - centre.x) * inverse.x, oy = (py[k] - centre.y) * inverse.y,
                oz = (pz[k] - centre.z) * inverse.z;
        const C dx = tx[k] * inverse.x, dy = ty[k] * inverse.y, dz = tz[k] * inverse.z;
        const C o_o = ox * ox + oy * oy + oz * oz, a = dx * dx + dy * dy + dz * dz;
        const C usable = mask(o_o <= C(1e4)) * mask(a >= C(1e-4));
        const C b = ox * dx + oy * dy + oz * dz;
        const C disc = b * b - a * (o_o - C(1));
        const C misses = mask(disc < C(-1e-6) * a), crosses = mask(disc > C(1e-3) * a);
        const C root = sqrt(disc);
        const C near = -b - root, far = -b + root;
        const C in_lo = (lo + margin) * a, in_hi = (C(1) - margin) * a;
        const C out_lo = (lo - margin) * a, out_hi = (C(1) + margin) * a;
        const C near_in = mask(near > in_lo) * mask(near < in_hi);
        const C far_in = mask(far > in_lo) * mask(far < in_hi);
        const C near_out = mask(near < out_lo) + mask(near > out_hi);  // at most one holds
        const C far_out = mask(far < out_lo) + mask(far > out_hi);
        const C any_in = near_in + far_in - near_in * far_in;
        const C yes = usable * crosses * any_in;
        // misses and crosses exclude each other; a lane with a root clearly in is not
        // clearly out.
        const C no = usable * (misses + crosses * near_out * far_out);
        out.blocked[k] = yes;
        out.unsure[k] = C(1) - yes - no;
    }
    return out;
}

}  // namespace rt
