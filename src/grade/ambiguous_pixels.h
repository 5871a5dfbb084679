// The keys' known ambiguous pixels (SPEC section 7): the eye rays whose outcome depends on
// the last bit of the arithmetic, so that the key records one arbitrary outcome and a
// correct renderer may record the other. The only table of them; the pass rule reads it.
#pragma once

#include <string>
#include <vector>

namespace grade {

struct AmbiguousPixel {
    const char* key;  // the key's file stem, "keyShadow"
    int x, y;         // column, row from the top
    const char* reason;
};

// Every entry of the table.
const std::vector<AmbiguousPixel>& ambiguous_pixels();
// The entries of one key.
std::vector<AmbiguousPixel> ambiguous_pixels_of(const std::string& key);

}  // namespace grade
