// How two images differ, pixel by pixel: the tests' and the benchmark's comparison of a
// fast path's image with the reference's (the grader judges with its own pass rule,
// src/grade/pass_rule.h).
#pragma once

#include <cstddef>

#include "raytracer/image.h"

struct ImageDiff {
    bool same_size = false;
    long long differing_pixels = 0;  // pixels where any channel differs
    int largest_difference = 0;      // the largest channel difference, in levels
};

inline ImageDiff compare_images(const rt::Image& a, const rt::Image& b) {
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
