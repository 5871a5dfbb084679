// intersect() (ellipsoid.h) for N rays against one ellipsoid at once, ray k in lane k:
// the rays of a bundle in the tree's leaves (slab_rays.h), and the flat sweep's mirrored
// rays of a packet of hits (PacketTracer::reflections()).
//
// WHY: one ray at a time, intersect() is seven divisions (three for o', three for d', one
// in unit_roots()) and a square root with branches in between (in the mirror room of
// tests/bench/heavy.txt, where every hit reflects, a fifth of the flat sweep's time). Here the lanes run the
// one root solver, unit_sphere_roots(), in a loop that GCC and Clang turn into vector instructions (which
// round as scalar ones do: no fused multiply-adds, CMakeLists.txt), on the same inputs intersect() gives it:
// each lane gets intersect()'s roots bit for bit.
#pragma once

#include "raytracer/compiler.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/unit_sphere_roots.h"

namespace rt {

// Per lane k: hit[k] = 1 where intersect(e, (ox, oy, oz)[k], (dx, dy, dz)[k]).hit (else 0),
// and there near[k], far[k] its roots.
template <int N, typename Real>
void intersect_lanes(const Ellipsoid<Real>& e, const Real* ox, const Real* oy, const Real* oz, const Real* dx,
                     const Real* dy, const Real* dz, Real* hit, Real* near, Real* far) {
    const Vec3<Real> scale = e.scale;
    // Results into local arrays first: with three output pointers that may alias the
    // inputs GCC gives up on the run-time alias checks and keeps the loop scalar.
    Real hits[N], nears[N], fars[N];
    RT_VECTOR_LOOP
    for (int k = 0; k < N; ++k) {
        const MappedOrigin<Real> o = mapped_origin(e, Vec3<Real>{ox[k], oy[k], oz[k]});
        // intersect_mapped(): d / s.
        const Roots<Real> r =
            unit_sphere_roots(o.o.x, o.o.y, o.o.z, o.c, dx[k] / scale.x, dy[k] / scale.y, dz[k] / scale.z);
        hits[k] = r.hit, nears[k] = r.near, fars[k] = r.far;
    }
    for (int k = 0; k < N; ++k) hit[k] = hits[k], near[k] = nears[k], far[k] = fars[k];
}

}  // namespace rt
