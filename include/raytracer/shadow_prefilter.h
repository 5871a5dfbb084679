// Decides most shadow-ray tests without intersect()'s divisions, and defers to it
// only where its answer could be close.
//
// WHY: a shadow ray needs only yes/no, "some root in (0.001, 1)". Computing the roots
// in the unit sphere's space with products by reciprocal scales (instead of the exact
// quotients) gives them, as intersect() does, to within about 1e-6 when the origin is
// not far away (|o'| <= 100) and the ray not too short (|d'| >= 1e-2). Where the mapped
// line clearly misses (1 - |l|^2 < -1e-6) or clearly crosses (> 1e-3) and every root
// is at least 1e-4 from
// 0.001 and 1, intersect() must give the same answer; everything else (tangent rays,
// roots near the limits, float, far or tiny rays) runs intersect() as before. Images
// stay bit-identical. Measured gain in docs/speed.md.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

#include "raytracer/ellipsoid.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real>
class ShadowPrefilter {
public:
    using C = std::conditional_t<(sizeof(Real) > sizeof(double)), Real, double>;
    enum Answer { kUnsure, kClear, kBlocked };

    ShadowPrefilter() = default;

    explicit ShadowPrefilter(const std::vector<Ellipsoid<Real>>& ellipsoids) {
        // float's own rounding (1e-7 relative) is too close to the margins below.
        if (std::numeric_limits<Real>::digits < std::numeric_limits<double>::digits) return;
        for (const Ellipsoid<Real>& e : ellipsoids) {
            centre_.push_back(Vec3<C>::from(e.centre));
            inverse_scale_.push_back({C(1) / C(e.scale.x), C(1) / C(e.scale.y), C(1) / C(e.scale.z)});
        }
    }

    // Whether ellipsoid i blocks the shadow ray point + t to_light, 0.001 < t < 1.
    Answer decide(const Vec3<Real>& point, const Vec3<Real>& to_light, std::size_t i) const {
        if (centre_.empty()) return kUnsure;
        using std::sqrt;
        const Vec3<C> o = (Vec3<C>::from(point) - centre_[i]) * inverse_scale_[i];
        const Vec3<C> d = Vec3<C>::from(to_light) * inverse_scale_[i];
        const C o2 = dot(o, o), a = dot(d, d);
        if (!(o2 <= C(1e4) && a >= C(1e-4))) return kUnsure;
        const C b = dot(o, d);
        const Vec3<C> l = o - d * (b / a);
        const C h = C(1) - dot(l, l);  // (b^2 - a c) / a
        if (h < C(-1e-6)) return kClear;
        if (!(h > C(1e-3))) return kUnsure;
        const C root = sqrt(a * h);
        const C near = (-b - root) / a, far = (-b + root) / a;
        const C lo = C(kShadowMinT), margin = C(1e-4);
        auto clearly_in = [&](C t) { return t > lo + margin && t < C(1) - margin; };
        auto clearly_out = [&](C t) { return t < lo - margin || t > C(1) + margin; };
        if (clearly_in(near) || clearly_in(far)) return kBlocked;
        if (clearly_out(near) && clearly_out(far)) return kClear;
        return kUnsure;
    }

private:
    static constexpr double kShadowMinT = 0.001;  // as rt::kShadowRayMinT (tracer.h)

    std::vector<Vec3<C>> centre_, inverse_scale_;
};

}  // namespace rt
