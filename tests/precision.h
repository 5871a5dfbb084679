// Renders a scene in a precision chosen at run time and measures how far one image is
// from another. Shared by the precision tests, the metamorphic tests and the benchmark.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "image_diff.h"
#include "raytracer/image.h"
#include "raytracer/render.h"
#include "raytracer/scene.h"

namespace precision {

enum class Real { kFloat, kDouble, kLongDouble };

inline const char* name_of(Real real) {
    if (real == Real::kFloat) return "float";
    if (real == Real::kDouble) return "double";
    return "long double";
}

// On one thread, so that the report's times compare the precisions and not the cores.
inline rt::Image render(const rt::Scene& scene, Real real) {
    if (real == Real::kFloat) return rt::render<float>(scene, 1);
    if (real == Real::kDouble) return rt::render<double>(scene, 1);
    return rt::render<long double>(scene, 1);
}

// How far an image is from a reference of the same size.
struct Error {
    long long differing_pixels = 0;  // pixels where any channel differs
    long long pixels = 0;
    int largest_difference = 0;                             // in levels, 0..255
    double psnr = std::numeric_limits<double>::infinity();  // dB over all channels; infinite when equal
};

inline Error error_of(const rt::Image& image, const rt::Image& reference) {
    Error e;
    const ImageDiff diff = compare_images(image, reference);
    e.pixels = static_cast<long long>(reference.width) * reference.height;
    if (!diff.same_size) {
        e.differing_pixels = e.pixels;
        e.largest_difference = 255;
        e.psnr = 0;
        return e;
    }
    e.differing_pixels = diff.differing_pixels;
    e.largest_difference = diff.largest_difference;
    double squares = 0;
    for (std::size_t i = 0; i < image.rgb.size(); ++i) {
        const double d = double(image.rgb[i]) - double(reference.rgb[i]);
        squares += d * d;
    }
    if (squares > 0) e.psnr = 10 * std::log10(255.0 * 255.0 * double(image.rgb.size()) / squares);
    return e;
}

inline double differing_percent(const Error& e) {
    return e.pixels > 0 ? 100.0 * double(e.differing_pixels) / double(e.pixels) : 0;
}

}  // namespace precision
