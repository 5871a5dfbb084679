// The reference path: each pixel on its own through Whitted (whitted.h) with BruteForce
// (brute_force.h), every ray against every ellipsoid: `raytracer.exe --reference`, and
// what the tests hold every other path to, byte for byte.
#include <cstddef>
#include <cstdint>

#include "raytracer/image.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/whitted.h"
#include "raytracer/render.h"
#include "raytracer/render_bands.h"

namespace rt {

template <typename Real>
void render_reference_to(const Scene& scene, RowSink& sink, unsigned threads) {
    const Whitted<Real, BruteForce<Real>> tracer(scene, BruteForce<Real>(make_ellipsoids<Real>(scene)));
    render_bands(
        scene, sink, threads, [&] { return tracer.make_scratch(); },
        [&](int first_row, int rows, std::uint8_t* const* out, auto& scratch) {
            for (int j = 0; j < rows; ++j) {
                for (int c = 0; c < scene.columns; ++c) {
                    tracer.pixel(c, first_row + j, out[j] + bytes_of_pixels(c), scratch);
                    if (c % 4 == 3) sink.still_rendering();  // a row of a large scene takes seconds here
                }
            }
        });
}

// As render.cpp: double for raytracer.exe (--reference), float and long double for the
// tests and the precision report.
#ifdef RAYTRACER_EXTRA_PRECISIONS
template void render_reference_to<float>(const Scene&, RowSink&, unsigned);
template void render_reference_to<long double>(const Scene&, RowSink&, unsigned);
#else
template void render_reference_to<double>(const Scene&, RowSink&, unsigned);
#endif

}  // namespace rt
