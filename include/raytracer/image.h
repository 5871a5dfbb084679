// An 8-bit RGB image, rows from the top, and the pixel-by-pixel comparison that the
// grader and the golden-image tests share.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rt {

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // width * height * 3 bytes, top-left pixel first
};

struct ImageDiff {
    bool same_size = false;
    long long differing_pixels = 0;  // pixels where any channel differs
    int largest_difference = 0;      // the largest channel difference, in levels
};

ImageDiff compare_images(const Image& a, const Image& b);

// SPEC section 6: clamp to [0, 1], scale by 255, truncate. NaN gives 0.
template <typename Real>
std::uint8_t to_byte(Real channel) {
    if (channel >= Real(1)) return 255;
    if (channel > Real(0)) return static_cast<std::uint8_t>(channel * Real(255));
    return 0;
}

}  // namespace rt
