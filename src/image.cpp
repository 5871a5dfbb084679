// Pixel-by-pixel comparison of two images, shared by the grader and the tests.
#include "raytracer/image.h"

namespace rt {

ImageDiff compare_images(const Image& a, const Image& b) {
    ImageDiff diff;
    diff.same_size = a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size();
    if (!diff.same_size) return diff;
    for (std::size_t i = 0; i < a.rgb.size(); i += 3) {
        int largest = 0;
        for (std::size_t k = i; k < i + 3; ++k) {
            const int d = a.rgb[k] > b.rgb[k] ? a.rgb[k] - b.rgb[k] : b.rgb[k] - a.rgb[k];
            if (d > largest) largest = d;
        }
        if (largest > 0) ++diff.differing_pixels;
        if (largest > diff.largest_difference) diff.largest_difference = largest;
    }
    return diff;
}

}  // namespace rt
