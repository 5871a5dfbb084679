// The rules of SPEC sections 3-5 that decide, per ray and ellipsoid, what a root means:
// which root an eye or reflected ray sees, and whether a shadow ray is blocked. Every
// geometry query (brute_force.h, bvh.h) decides with these, so that they agree bit for bit.
#pragma once

#include <cstdint>

#include "raytracer/ellipsoid.h"
#include "raytracer/scene_precision.h"

namespace rt {

// Epsilons and limits that the course keys fix (SPEC sections 3 and 5).
namespace spec {
inline constexpr double kEyeRayMinT = 1.0;       // the near plane is at t = 1
inline constexpr double kShadowRayMinT = 0.001;  // the keys need 0.001, not 0.0001
inline constexpr double kReflectedRayMinT = 0.0001;
inline constexpr int kMaxReflections = 3;
}  // namespace spec

// The ray parameter beyond which a root is visible, for a ray that starts at min_t. A
// root computed within a few ulps of min_t cannot be told from one at min_t, and one at
// min_t is not visible (the hit must lie beyond it). This decides the eye rays through
// the rim where the near plane cuts an ellipsoid: keyIllum's pixels (240,345),
// (360,345), (345,240), (345,360) have their far root at exactly t = 1 (a 3-4-5
// triangle), which double rounding puts 2 ulps above 1. The ulps are those of the
// scene's double numbers, whatever Real is (scene_precision.h), so that long double
// decides these pixels as double does.
template <typename Real>
Real visible_beyond(double min_t) {
    return Real(min_t) * (Real(1) + Real(8) * scene_epsilon<Real>());
}

// The root a ray sees of an ellipsoid it meets, given visible_beyond(): the near root
// when it lies beyond the limit, else the far one (the ray starts inside, or the near
// plane cuts the ellipsoid: it is seen hollow). Returns false when neither is visible.
template <typename Real>
bool visible_root(const Roots<Real>& r, Real beyond, Real& t, bool& inside) {
    if (!r.hit) return false;
    inside = !(r.near > beyond);
    t = inside ? r.far : r.near;
    return t > beyond;
}

// Whether a shadow ray from a point towards a light at t = 1 is blocked by an ellipsoid
// with these roots: a root strictly between kShadowRayMinT and the light.
template <typename Real>
bool blocks_shadow_ray(const Roots<Real>& r) {
    const Real min_t = Real(spec::kShadowRayMinT);
    return r.hit && ((r.near > min_t && r.near < 1) || (r.far > min_t && r.far < 1));
}

// A geometry's hint for its any-hit query, per light and thread: which ellipsoid to try
// first (the one that blocked this light last); kNoBlocker before any.
inline constexpr std::uint32_t kNoBlocker = 0xFFFFFFFFU;

// The answer of a closest-hit query: the ellipsoid a ray sees first, at t.
template <typename Real>
struct NearestHit {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFU;
    std::uint32_t ellipsoid = kNone;
    Real t = 0;
    bool inside = false;  // the far root was taken: the ray sees the inside

    bool found() const { return ellipsoid != kNone; }
    // Whether root t of ellipsoid i is to replace this hit. Equal roots go to the lower
    // index, as in a loop over the ellipsoids in the file's order, whatever order a
    // query visits them in.
    bool replaced_by(Real root, std::uint32_t i) const {
        return !found() || root < t || (root == t && i < ellipsoid);
    }
};

}  // namespace rt
