// The precision of the scene's own numbers. The scene is parsed into double whatever
// precision renders it (parsing stays single), so each number already carries a
// relative rounding error of up to DBL_EPSILON/2 from its decimal text: 0.6 is stored
// as 0.59999999999999997780. Decisions that the decimal scene puts exactly on a
// boundary (a tangent ray, a hit on the near plane, a colour of exactly 153/255) are
// therefore settled with a tolerance of the scene's precision, not of the working
// precision, so that the double and the long double render decide them alike; float,
// whose own epsilon is coarser, uses its own. This is the backward-error view: a result
// is as good as the data when it is exact for data perturbed within their own
// uncertainty (N. J. Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed.,
// SIAM 2002, section 1.5).
#pragma once

#include <limits>
#include <type_traits>

namespace rt {

template <typename Real>
constexpr Real scene_epsilon() {
    return std::numeric_limits<Real>::epsilon() > Real(std::numeric_limits<double>::epsilon())
               ? std::numeric_limits<Real>::epsilon()
               : Real(std::numeric_limits<double>::epsilon());
}

// The exact shortcuts of the fast path (culling, prefilters) compute in double at least:
// float would leave too little room between its own rounding and their safety margins.
template <typename Real>
using AtLeastDouble = std::conditional_t<(sizeof(Real) > sizeof(double)), Real, double>;

}  // namespace rt
