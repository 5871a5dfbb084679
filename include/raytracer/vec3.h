// A three-component vector over any floating-point type. The render core is a
// template on the scalar (float, double, long double), so this is too.
#pragma once

#include <cmath>

#include "raytracer/compiler.h"

namespace rt {

template <typename Real>
struct Vec3 {
    Real x{}, y{}, z{};

    constexpr Vec3() = default;
    constexpr Vec3(Real x_, Real y_, Real z_) : x(x_), y(y_), z(z_) {}

    template <typename Other>
    static constexpr Vec3 from(const Vec3<Other>& v) {
        return {static_cast<Real>(v.x), static_cast<Real>(v.y), static_cast<Real>(v.z)};
    }

    RT_ALWAYS_INLINE constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    RT_ALWAYS_INLINE constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    RT_ALWAYS_INLINE constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    RT_ALWAYS_INLINE constexpr Vec3 operator*(Real k) const { return {x * k, y * k, z * k}; }
    // Componentwise product and quotient: the ellipsoid maps rays by its scales.
    RT_ALWAYS_INLINE constexpr Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }
    RT_ALWAYS_INLINE constexpr Vec3 operator/(const Vec3& o) const { return {x / o.x, y / o.y, z / o.z}; }
    RT_ALWAYS_INLINE Vec3& operator+=(const Vec3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
};

template <typename Real>
constexpr Vec3<Real> operator*(Real k, const Vec3<Real>& v) {
    return v * k;
}

template <typename Real>
RT_ALWAYS_INLINE constexpr Real dot(const Vec3<Real>& a, const Vec3<Real>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <typename Real>
RT_ALWAYS_INLINE Real length(const Vec3<Real>& v) {
    using std::sqrt;
    return sqrt(dot(v, v));
}

template <typename Real>
RT_ALWAYS_INLINE Vec3<Real> normalize(const Vec3<Real>& v) {
    return v * (Real(1) / length(v));
}

}  // namespace rt
