// The specular power (R.V)^n of SPEC section 5 without pow() where n is a whole number.
//
// WHY: std::pow is a general log/exp evaluation (about 17 ns here); the course's and
// most scenes' exponents are whole numbers, for which binary exponentiation needs at
// most 2 log2(n) multiplications, and these vectorise across lights (shade()).
//
// Accuracy: each squaring doubles the relative error carried so far and adds half an
// ulp, so x^n is within about n ulps of the exact power (N. J. Higham, Accuracy and
// Stability of Numerical Algorithms, 2nd ed., SIAM 2002, section 3.1 on products); the
// specular term is then off by at most n * 1.1e-16 of itself, which moves a colour
// byte only where the exact value lies that close to a truncation step (the keys, the
// hard scenes and 160 more scenes render the same bytes as with std::pow:
// docs/speed.md). A power that is exactly representable (x = 0.5, n = 3) is computed
// exactly, as every partial product then is. Exponents that are not whole, negative
// or above kMaxWholeExponent still go to std::pow (the error bound grows with n).
#pragma once

#include <cmath>
#include <cstdint>

namespace rt {

inline constexpr double kMaxWholeExponent = 65536;

// n as a whole-number exponent for whole_power(), or -1 when pow() must be used.
template <typename Real>
std::int32_t whole_exponent(Real n) {
    if (!(n >= 0 && n <= Real(kMaxWholeExponent))) return -1;
    const auto k = static_cast<std::int32_t>(n);
    return Real(k) == n ? k : -1;
}

// x^k by binary exponentiation (right to left), k >= 0.
template <typename Real>
Real whole_power(Real x, std::int32_t k) {
    Real result = 1;
    for (; k != 0; k >>= 1) {
        if (k & 1) result *= x;
        x *= x;
    }
    return result;
}

// x^n, with k = whole_exponent(n) computed once per material.
template <typename Real>
Real specular_power(Real x, Real n, std::int32_t k) {
    using std::pow;
    return k >= 0 ? whole_power(x, k) : pow(x, n);
}

}  // namespace rt
