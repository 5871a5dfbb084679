// The keys' known ambiguous pixels (SPEC section 7): the eye rays whose outcome depends on
// the last bit of the arithmetic, so that the key records one arbitrary outcome and a
// correct renderer may record the other. The only table of them; the pass rule reads it.
// Each holds the other outcome's colour, so that the pixel may differ from the key only
// by showing it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace grade {

struct AmbiguousPixel {
    const char* key;  // the key's file stem, "keyShadow"
    int x, y;         // column, row from the top
    // The pixel's bytes where its ray falls the other way from the key's (hit where the
    // key misses, or the reverse): the reference's colour for rays a billionth of a pixel
    // to that side (grade.ambiguous-outcomes derives each from the course scenes).
    std::array<std::uint8_t, 3> other;
    const char* reason;
};

// Every entry of the table.
const std::vector<AmbiguousPixel>& ambiguous_pixels();
// The entries of one key.
std::vector<AmbiguousPixel> ambiguous_pixels_of(const std::string& key);

}  // namespace grade
