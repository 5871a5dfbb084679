// The lowest set bit of a lane or ellipsoid set, for loops over the set bits only.
//
// WHY: a loop over every bit position, testing each, branches once per position on
// data that changes from packet to packet; a loop from lowest set bit to lowest set bit
// branches once per member (measured: callgrind's branch simulation, heavy scene).
#pragma once

#include <cstdint>

#if defined(_MSC_VER) && !defined(__clang__)
#include <intrin.h>
#endif

namespace rt {

// The index of the lowest set bit of x, which is not 0.
inline int lowest_bit(std::uint64_t x) {
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctzll(x);
#elif defined(_MSC_VER) && defined(_M_X64)
    unsigned long index = 0;
    _BitScanForward64(&index, x);
    return static_cast<int>(index);
#else
    int index = 0;
    for (; (x & 1U) == 0; x >>= 1) ++index;
    return index;
#endif
}

// How many bits of x are set.
inline int bit_count(std::uint64_t x) {
    int count = 0;
    for (; x != 0; x &= x - 1) ++count;
    return count;
}

}  // namespace rt
