// The specular power (R.V)^n of SPEC section 5 without pow() where n is a whole number.
//
// WHY: std::pow is a general log/exp evaluation, the time of tens of multiplications;
// the course's and most scenes' exponents are whole numbers, for which binary
// exponentiation needs at most 2 log2(n) multiplications, and these run lane by lane
// over the fast paths' rays, each lane with its own exponent, as vector instructions.
//
// Accuracy: each squaring doubles the relative error carried so far and adds half an
// ulp, so x^n is within about n ulps of the exact power (N. J. Higham, Accuracy and
// Stability of Numerical Algorithms, 2nd ed., SIAM 2002, section 3.1 on products); the
// specular term is then off by at most n * 1.1e-16 of itself, which moves a colour
// byte only where the exact value lies that close to a truncation step (measured on the
// keys, the hard scenes, our scenes and 120 random scenes: the same bytes as with
// std::pow; tests/unit_shading.cpp checks the bound). A power that is exactly
// representable (x = 0.5, n = 3) is computed exactly, as every partial product then is.
// Exponents that are not whole, negative or above kMaxWholeExponent still go to
// std::pow (the error bound grows with n).
#pragma once

#include <cstdint>
#include <type_traits>

#include "raytracer/compiler.h"
#include "raytracer/reference/masks.h"

namespace rt {

// At most 32 multiplications, and within 65,536 ulps (7e-12 of the term in double).
inline constexpr double kMaxWholeExponent = 65536;

// n as a whole-number exponent for whole_power(), or -1 when pow() must be used.
template <typename Real>
std::int32_t whole_exponent(Real n) {
    if (!(n >= 0 && n <= Real(kMaxWholeExponent))) return -1;
    const auto k = static_cast<std::int32_t>(n);
    return Real(k) == n ? k : -1;
}

// x^k by binary exponentiation (right to left), k >= 0. For one ray (Real, int32) or
// for lanes (lanes.h), each lane with its own k: a lane's product takes the factor only
// where its own bit is set, so it is the scalar's product, bit for bit.
template <typename T, typename K>
RT_ALWAYS_INLINE T whole_power(T x, K k) {
    T result = T(1);
    if constexpr (std::is_arithmetic_v<K>) {
        // One exponent: a branch rather than a select, which GCC compiles for lanes
        // into stores and loads of the product each turn.
        for (; k != 0; k >>= 1) {
            if ((k & 1) != 0) result = result * x;
            x = x * x;
        }
    } else {
        for (; any(k != K(0)); k = k >> 1) {
            result = select((k & K(1)) != K(0), result * x, result);
            x = x * x;
        }
    }
    return result;
}

// x^n, with k = whole_exponent(n) computed once per material.
template <typename T, typename K>
RT_ALWAYS_INLINE T specular_power(T x, T n, K k) {
    const MaskOf<T> whole = k >= K(0), fractional = k < K(0);
    const T power = whole_power(x, select(whole, k, K(0)));
    return any(fractional) ? select(whole, power, pow_where(fractional, x, n)) : power;
}

}  // namespace rt
