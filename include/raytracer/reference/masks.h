// Branches written once for one ray and for lanes of rays (lanes.h): a comparison gives a
// mask, a bool for one ray and LaneBits (bit k for lane k) for lanes. Where code for one
// ray would branch, code written for both takes select(), asks any() whether some lane
// needs a term, and takes pow() only where a mask says (pow_where()), so a lane never
// gets a term its scalar run would have skipped. These are the one-ray forms; lanes.h
// gives the same names for lanes.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "raytracer/compiler.h"
#include "raytracer/vec3.h"

namespace rt {

using LaneBits = std::uint64_t;  // a mask of lanes, bit k for lane k (64 bits, as a lane of doubles)

template <typename Real, typename = std::enable_if_t<std::is_arithmetic_v<Real>>>
RT_ALWAYS_INLINE Real select(bool where, Real a, Real b) {
    return where ? a : b;
}
template <typename Real, typename = std::enable_if_t<std::is_arithmetic_v<Real>>>
Real pow_where(bool where, Real x, Real n) {
    using std::pow;
    return where ? pow(x, n) : Real(0);
}
inline bool any(bool where) { return where; }
inline bool any(LaneBits where) { return where != 0; }

// A vector's select, for one ray or lanes.
template <typename Mask, typename T>
RT_ALWAYS_INLINE Vec3<T> select(Mask where, const Vec3<T>& a, const Vec3<T>& b) {
    return {select(where, a.x, b.x), select(where, a.y, b.y), select(where, a.z, b.z)};
}

// The mask a comparison of two T gives: bool for one ray, LaneBits for lanes; and the
// integers that go with T (a whole exponent per ray; lanes.h gives Lanes' own).
template <typename T>
using MaskOf = decltype(T() > T());
template <typename T>
struct IntegerOfT {
    using type = std::int32_t;
};
template <typename T>
using IntegerOf = typename IntegerOfT<T>::type;

}  // namespace rt
