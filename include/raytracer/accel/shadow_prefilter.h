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

#include "raytracer/accel/intersect_lanes.h"
#include "raytracer/bit_scan.h"
#include "raytracer/compiler.h"
#include "raytracer/lanes.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

// The prefilter's answers for N rays: bit k for ray k.
struct PrefilterAnswer {
    LaneBits blocked, unsure;
};

// Whether ellipsoid e blocks the shadow ray point + t to_light, 0.001 < t < 1, for N rays
// at once, ray k from (px, py, pz)[k] along (tx, ty, tz)[k]: in blocked where it clearly
// does, in unsure where intersect() must decide, else in neither. The roots' common
// factor 1/a is multiplied out (a > 0): a t = -b -+ sqrt(b^2 - a c) against a times each
// limit. With |o'|^2 <= 1e4 and a >= 1e-4, b^2 - a c is off by a few ulps of a |o'|^2, so
// h = (b^2 - a c) / a by under 1e-11 and the roots by under 1e-8: far inside the margins.
// The tests' branches are products of 0/1 masks (doubles: bool temporaries and && keep
// GCC's loops scalar), so the loop runs as vector instructions; a lane that a branch
// would have stopped computes values (even NaN from a negative sqrt) that no mask takes.
template <int N, typename Real>
PrefilterAnswer prefilter_shadow_lanes(const Ellipsoid<Real>& e, const Real* px, const Real* py,
                                       const Real* pz, const Real* tx, const Real* ty, const Real* tz) {
    // float's own rounding (1e-7 relative) is too close to the margins below.
    static_assert(std::numeric_limits<Real>::digits >= std::numeric_limits<double>::digits,
                  "the prefilter needs double or wider");
    auto mask = [](bool b) { return b ? Real(1) : Real(0); };
    Real blocked[N], unsure[N];
    using std::sqrt;
    const Vec3<Real> centre = e.centre,
                     inverse{Real(1) / e.scale.x, Real(1) / e.scale.y, Real(1) / e.scale.z};
    const Real lo = Real(kShadowRayMinT), margin = Real(1e-4);
    RT_VECTOR_LOOP
    for (int k = 0; k < N; ++k) {
        const Real ox = (px[k] - centre.x) * inverse.x, oy = (py[k] - centre.y) * inverse.y,
                   oz = (pz[k] - centre.z) * inverse.z;
        const Real dx = tx[k] * inverse.x, dy = ty[k] * inverse.y, dz = tz[k] * inverse.z;
        const Real o_o = ox * ox + oy * oy + oz * oz, a = dx * dx + dy * dy + dz * dz;
        const Real usable = mask(o_o <= Real(1e4)) * mask(a >= Real(1e-4));
        const Real b = ox * dx + oy * dy + oz * dz;
        const Real disc = b * b - a * (o_o - Real(1));
        const Real misses = mask(disc < Real(-1e-6) * a), crosses = mask(disc > Real(1e-3) * a);
        const Real root = sqrt(disc);
        const Real near = -b - root, far = -b + root;
        const Real in_lo = (lo + margin) * a, in_hi = (Real(1) - margin) * a;
        const Real out_lo = (lo - margin) * a, out_hi = (Real(1) + margin) * a;
        const Real near_in = mask(near > in_lo) * mask(near < in_hi);
        const Real far_in = mask(far > in_lo) * mask(far < in_hi);
        const Real near_out = mask(near < out_lo) + mask(near > out_hi);  // at most one holds
        const Real far_out = mask(far < out_lo) + mask(far > out_hi);
        const Real any_in = near_in + far_in - near_in * far_in;
        const Real yes = usable * crosses * any_in;
        // misses and crosses exclude each other; a lane with a root clearly in is not
        // clearly out.
        const Real no = usable * (misses + crosses * near_out * far_out);
        blocked[k] = yes;
        unsure[k] = Real(1) - yes - no;
    }
    PrefilterAnswer answer{0, 0};
    RT_VECTOR_LOOP
    for (int k = 0; k < N; ++k) {
        answer.blocked |= blocked[k] != 0 ? kLaneBits<N>.bit[k] : 0;
        answer.unsure |= unsure[k] != 0 ? kLaneBits<N>.bit[k] : 0;
    }
    return answer;
}

// The lanes of `lanes` whose shadow ray ellipsoid e blocks (blocks_segment()), ray k from
// (px, py, pz)[k] along (tx, ty, tz)[k]: the answers intersect() gives, lane by lane. In
// double or wider the prefilter decides nearly all (the heavy scene through the tree:
// all but 912 of 1.77 million lanes), and intersect() the few it leaves, one at a time;
// in float, intersect() decides every lane, in one vector loop (intersect_lanes()).
template <int N, typename Real>
LaneBits blocked_lanes(const Ellipsoid<Real>& e, const Real* px, const Real* py, const Real* pz,
                       const Real* tx, const Real* ty, const Real* tz, LaneBits lanes) {
    if constexpr (std::numeric_limits<Real>::digits >= std::numeric_limits<double>::digits) {
        const PrefilterAnswer answer = prefilter_shadow_lanes<N>(e, px, py, pz, tx, ty, tz);
        LaneBits blocked = answer.blocked & lanes;
        for (LaneBits unsure = answer.unsure & lanes; unsure != 0; unsure &= unsure - 1) {
            const int k = lowest_bit(unsure);
            if (blocks_segment(e, Vec3<Real>{px[k], py[k], pz[k]}, Vec3<Real>{tx[k], ty[k], tz[k]}))
                blocked |= LaneBits(1) << k;
        }
        return blocked;
    } else {
        Real hit[N], near[N], far[N];
        intersect_lanes<N>(e, px, py, pz, tx, ty, tz, hit, near, far);
        LaneBits blocked = 0;
        for (; lanes != 0; lanes &= lanes - 1) {
            const int k = lowest_bit(lanes);
            if (blocks_segment(Roots<Real>{hit[k], near[k], far[k]})) blocked |= LaneBits(1) << k;
        }
        return blocked;
    }
}

}  // namespace rt
