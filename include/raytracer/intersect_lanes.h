// intersect() (ellipsoid.h) for N rays against one ellipsoid at once, ray k in lane k.
//
// WHY: the mirrored rays of a packet of hits (Tracer::reflections()) were searched one
// at a time: per ray a culling pass over all bounding spheres, then intersect() on each
// candidate, four divisions and a square root with branches in between. In the mirror
// room of tests/bench/heavy.txt every hit reflects, so this was a fifth of the time.
// Here every lane performs intersect()'s operations in intersect()'s order, its early
// returns turned into selects, so that GCC and Clang run the lanes as vector
// instructions (which round as scalar ones do: no fused multiply-adds, CMakeLists.txt);
// each lane gets intersect()'s roots bit for bit. A lane whose branch intersect() would
// not reach computes values (even NaN) that no select takes.
#pragma once

#include <cmath>

#include "raytracer/compiler.h"
#include "raytracer/ellipsoid.h"
#include "raytracer/scene_precision.h"

namespace rt {

// Per lane k: hit[k] = 1 where intersect(e, (ox, oy, oz)[k], (dx, dy, dz)[k]).hit (else 0),
// and there near[k], far[k] its roots.
template <int N, typename Real>
void intersect_lanes(const Ellipsoid<Real>& e, const Real* ox, const Real* oy, const Real* oz, const Real* dx,
                     const Real* dy, const Real* dz, Real* hit, Real* near, Real* far) {
    using std::abs;
    using std::sqrt;
    const Vec3<Real> centre = e.centre, scale = e.scale;
    const Real tangent = -Real(4) * scene_epsilon<Real>();
    // Results into local arrays first: with three output pointers that may alias the six
    // inputs GCC gives up on the run-time alias checks and keeps the loop scalar.
    Real hits[N], nears[N], fars[N];
    for (int k = 0; k < N; ++k) {
        // mapped_origin(): o = (origin - C) / s, c = o.o - 1.
        const Real mx = (ox[k] - centre.x) / scale.x, my = (oy[k] - centre.y) / scale.y,
                   mz = (oz[k] - centre.z) / scale.z;
        const Real c = (mx * mx + my * my + mz * mz) - Real(1);
        // intersect_mapped(): d = direction / s, a = d.d, b = o.d, l = o - d (b / a).
        const Real ux = dx[k] / scale.x, uy = dy[k] / scale.y, uz = dz[k] / scale.z;
        const Real a = ux * ux + uy * uy + uz * uz;
        const Real b = mx * ux + my * uy + mz * uz;
        const Real ratio = b / a;
        const Real lx = mx - ux * ratio, ly = my - uy * ratio, lz = mz - uz * ratio;
        const Real unit_disc = Real(1) - (lx * lx + ly * ly + lz * lz);
        // Below zero: a miss unless within the tangent allowance, where it counts as 0.
        // std::max(a, b) is (a < b) ? b : a. The allowance is never positive, so below it
        // is below zero. (Selects of Real values, no bool temporaries: those keep GCC's
        // loop scalar.)
        const Real ax = abs(mx), ay = abs(my), az = abs(mz);
        const Real yz = ay < az ? az : ay;
        const Real distance = ax < yz ? yz : ax;
        const Real allowance = tangent * (Real(1) + distance);
        const Real disc = unit_disc < 0 ? Real(0) : unit_disc;
        const Real root = sqrt(a * disc);
        const Real q = -(b + std::copysign(root, b));
        // q == 0: the roots are 0 and 0.
        const Real t1 = q / a, t2 = c / q;
        const Real lo = t1 > t2 ? t2 : t1, hi = t1 > t2 ? t1 : t2;
        hits[k] = unit_disc < allowance ? Real(0) : Real(1);
        nears[k] = q == 0 ? Real(0) : lo;
        fars[k] = q == 0 ? Real(0) : hi;
    }
    for (int k = 0; k < N; ++k) hit[k] = hits[k], near[k] = nears[k], far[k] = fars[k];
}

}  // namespace rt
