// Shadow rays that run inside an ellipsoid enclosing the light cannot be blocked by it:
// the flat sweep's tables of the rule of light_shells.h (why it is exact is stated there),
// per ellipsoid and light. Only used at double precision or wider. Measured gain in
// docs/speed.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "raytracer/accel/light_shells.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real>
class Enclosures {
public:
    using C = AtLeastDouble<Real>;

    Enclosures() = default;

    Enclosures(const std::vector<Ellipsoid<Real>>& ellipsoids, const std::vector<Vec3<Real>>& lights)
        : n_(ellipsoids.size()) {
        if (std::numeric_limits<Real>::digits < std::numeric_limits<double>::digits) return;
        for (const Ellipsoid<Real>& e : ellipsoids) {
            centre_.push_back(Vec3<C>::from(e.centre));
            inverse_scale_.push_back({C(1) / C(e.scale.x), C(1) / C(e.scale.y), C(1) / C(e.scale.z)});
        }
        light_inside_.assign(lights.size() * n_, 0);
        for (std::size_t l = 0; l < lights.size(); ++l)
            for (std::size_t i = 0; i < n_; ++i)
                light_inside_[l * n_ + i] = shell_holds_light(unit_radius2(Vec3<C>::from(lights[l]), i));
        any_light_inside_.assign(n_, 0);
        for (std::size_t l = 0; l < lights.size(); ++l)
            for (std::size_t i = 0; i < n_; ++i) any_light_inside_[i] |= light_inside_[l * n_ + i];
    }

    // True when the shadow ray from point to light light_index certainly is not blocked
    // by ellipsoid i because it runs inside it.
    bool contains_segment(const Vec3<Real>& point, std::size_t light_index, std::size_t i) const {
        return light_within(light_index, i) && point_within(unit_radius2(Vec3<C>::from(point), i));
    }

    // For N points at once, (px, py, pz)[k], the lanes k where contains_segment() holds
    // for light light_index and ellipsoid i: bit k of the result is kLane[k]'s bit.
    // The same operations per lane as contains_segment(), as a loop GCC vectorises.
    template <int N>
    std::uint64_t contains_segments(const C* px, const C* py, const C* pz, std::size_t light_index,
                                    std::size_t i, const std::uint64_t* lane_bits) const {
        if (!light_within(light_index, i)) return 0;
        return points_within<N>(px, py, pz, i, lane_bits);
    }
    // Its part that does not depend on the light: the lanes whose points point_within()
    // ellipsoid i. Double precision or wider only.
    template <int N>
    std::uint64_t points_within(const C* px, const C* py, const C* pz, std::size_t i,
                                const std::uint64_t* lane_bits) const {
        const Vec3<C> centre = centre_[i], inverse = inverse_scale_[i];
        std::uint64_t within = 0;
        for (int k = 0; k < N; ++k) {
            const C x = (px[k] - centre.x) * inverse.x, y = (py[k] - centre.y) * inverse.y,
                    z = (pz[k] - centre.z) * inverse.z;
            within |= point_within(x * x + y * y + z * z) ? lane_bits[k] : 0;
        }
        return within;
    }

    // contains_segment() in two parts: light_within(light_index, i) &&
    // point_within(unit_radius2(point, i)); the packets ask the first per light and the
    // second once per packet (points_within()).
    bool light_within(std::size_t light_index, std::size_t i) const {
        return !light_inside_.empty() && light_inside_[light_index * n_ + i];
    }
    static bool point_within(C o2) { return shell_holds_point(o2); }
    // Whether light_within(l, i) holds for some light l.
    bool encloses_a_light(std::size_t i) const { return !any_light_inside_.empty() && any_light_inside_[i]; }

private:
    // |(p - centre) / scale|^2 of ellipsoid i (light_shells.h).
    C unit_radius2(const Vec3<C>& p, std::size_t i) const {
        return rt::unit_radius2(p, centre_[i], inverse_scale_[i]);
    }

    std::size_t n_ = 0;
    std::vector<Vec3<C>> centre_, inverse_scale_;
    std::vector<unsigned char> light_inside_;      // [light * n + ellipsoid]
    std::vector<unsigned char> any_light_inside_;  // per ellipsoid
};

}  // namespace rt
