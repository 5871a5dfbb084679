// The two geometry queries of the tracer, closest hit and any hit, by the definition:
// every ray is tried against every ellipsoid. The reference that the acceleration layer
// (bvh.h) is held to, byte for byte; raytracer.exe takes it with --reference only.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real>
class BruteForce {
public:
    using V = Vec3<Real>;

    explicit BruteForce(std::vector<Ellipsoid<Real>> ellipsoids) : ellipsoids_(std::move(ellipsoids)) {}

    // Ellipsoid i of the scene.
    const Ellipsoid<Real>& ellipsoid(std::uint32_t i) const { return ellipsoids_[i]; }

    // The nearest ellipsoid that origin + t direction meets at a visible root beyond
    // min_t (spec_rules.h).
    NearestHit<Real> closest(const V& origin, const V& direction, double min_t) const {
        const Real beyond = visible_beyond(Real(min_t));
        NearestHit<Real> best;
        const std::vector<Ellipsoid<Real>>& all = ellipsoids_;
        for (std::uint32_t i = 0; i < all.size(); ++i)
            best.offer(intersect(all[i], origin, direction), beyond, i);
        return best;
    }

    // Whether some ellipsoid blocks the shadow ray from point to the light at
    // point + to_light (spec_rules.h). blocker: the one that blocked last, tried first
    // (kNoEllipsoid for none), and set to the one found; the answer is the same whichever
    // is tried first.
    bool occluded(const V& point, const V& to_light, std::uint32_t& blocker) const {
        const std::vector<Ellipsoid<Real>>& all = ellipsoids_;
        if (blocker < all.size() && blocks_segment(all[blocker], point, to_light)) return true;
        for (std::uint32_t i = 0; i < all.size(); ++i)
            if (blocks_segment(all[i], point, to_light)) return blocker = i, true;
        return false;
    }

private:
    std::vector<Ellipsoid<Real>> ellipsoids_;
};

}  // namespace rt
