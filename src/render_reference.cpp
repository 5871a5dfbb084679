// The reference path: each pixel on its own through Whitted (whitted.h) with BruteForce
// (brute_force.h), every ray against every ellipsoid. The tests hold every other path
// to its bytes.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/whitted.h"
#include "raytracer/render.h"
#include "raytracer/render_bands.h"

namespace rt {

template <typename Real>
void render_reference_to(const Scene& scene, RowSink& sink, unsigned threads) {
    const Whitted<Real, BruteForce<Real>> tracer(scene, BruteForce<Real>(make_ellipsoids<Real>(scene)));
    const std::vector<Real> column_x = column_xs<Real>(scene);
    render_bands(
        scene, sink, threads, [&] { return tracer.make_scratch(); },
        [&](int first_row, int rows, std::uint8_t* const* out, auto& scratch) {
            for (int j = 0; j < rows; ++j) {
                const Real y = tracer.row_y(first_row + j);
                for (std::size_t c = 0; c < column_x.size(); ++c)
                    tracer.pixel(column_x[c], y, out[j] + c * 3, scratch);
            }
        });
}

template <typename Real>
Image render_reference(const Scene& scene, unsigned threads) {
    ImageSink sink(scene.columns, scene.rows);
    render_reference_to<Real>(scene, sink, threads);
    return std::move(sink.image);
}

// For the tests only (raytracer_precisions, CMakeLists.txt), in every precision:
// raytracer.exe never renders through the reference.
template void render_reference_to<float>(const Scene&, RowSink&, unsigned);
template void render_reference_to<double>(const Scene&, RowSink&, unsigned);
template void render_reference_to<long double>(const Scene&, RowSink&, unsigned);
template Image render_reference<float>(const Scene&, unsigned);
template Image render_reference<double>(const Scene&, unsigned);
template Image render_reference<long double>(const Scene&, unsigned);

}  // namespace rt
