// render_to(): the path a scene takes (docs/speed.md). The reference path for the
// tests; the tree (render_whitted.cpp) past the flat sweep's range (takes_the_tree());
// the flat sweep (flat_sweep/render_flat_sweep.cpp) within it.
#include "raytracer/render.h"

#include <cstddef>

#include "raytracer/flat_sweep/render_flat_sweep.h"
#include "raytracer/helper_pool.h"
#include "raytracer/render_whitted.h"

namespace rt {

#ifndef RAYTRACER_EXTRA_PRECISIONS  // (see the end of this file)
unsigned threads_asked(unsigned threads) { return threads == 0 ? available_cores() : threads; }
#endif

template <typename Real>
void render_to(const Scene& scene, RowSink& sink, unsigned threads, bool accelerate) {
    if (!accelerate) return render_reference_to<Real>(scene, sink, threads);
    if (takes_the_tree(scene)) return render_whitted_to<Real>(scene, sink, threads);
    render_flat_sweep_to<Real>(scene, sink, threads);
}

namespace {
// Collects the rows into an image.
struct ImageSink final : RowSink {
    Image& image;
    explicit ImageSink(Image& i) : image(i) {}
    void rows(const std::uint8_t* bytes, std::size_t size) override {
        image.rgb.insert(image.rgb.end(), bytes, bytes + size);
    }
};
}  // namespace

template <typename Real>
Image render(const Scene& scene, unsigned threads, bool accelerate) {
    Image image;
    image.width = scene.columns;
    image.height = scene.rows;
    image.rgb.reserve(static_cast<std::size_t>(scene.columns) * static_cast<std::size_t>(scene.rows) * 3);
    ImageSink sink(image);
    render_to<Real>(scene, sink, threads, accelerate);
    return image;
}

// raytracer.exe renders in double. The tests and the precision report render in float
// and long double too: this file is compiled a second time with RAYTRACER_EXTRA_PRECISIONS
// into raytracer_precisions (CMakeLists.txt) for those, so that the shipped program
// compiles one precision only (a third of the build).
#ifdef RAYTRACER_EXTRA_PRECISIONS
template void render_to<float>(const Scene&, RowSink&, unsigned, bool);
template void render_to<long double>(const Scene&, RowSink&, unsigned, bool);
template Image render<float>(const Scene&, unsigned, bool);
template Image render<long double>(const Scene&, unsigned, bool);
#else
template void render_to<double>(const Scene&, RowSink&, unsigned, bool);
template Image render<double>(const Scene&, unsigned, bool);
#endif

}  // namespace rt
