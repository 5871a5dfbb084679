#include "raytracer/render.h"

#include "raytracer/tracer.h"

namespace rt {

template <typename Real>
Image render(const Scene& scene) {
    const Tracer<Real> tracer(scene);
    Image image;
    image.width = scene.columns;
    image.height = scene.rows;
    image.rgb.resize(static_cast<std::size_t>(scene.columns) * static_cast<std::size_t>(scene.rows) * 3);

    const Real left = static_cast<Real>(scene.left), right = static_cast<Real>(scene.right);
    const Real bottom = static_cast<Real>(scene.bottom), top = static_cast<Real>(scene.top);
    const Real near_z = -static_cast<Real>(scene.near_plane);
    const Real columns = static_cast<Real>(scene.columns), rows = static_cast<Real>(scene.rows);

    TraceScratch scratch = tracer.make_scratch();
    std::uint8_t* out = image.rgb.data();
    for (int r = 0; r < scene.rows; ++r) {
        // The top-left corner of the pixel, not its centre: the keys demand it.
        const Real y = top - (top - bottom) * static_cast<Real>(r) / rows;
        for (int c = 0; c < scene.columns; ++c) {
            const Real x = left + (right - left) * static_cast<Real>(c) / columns;
            const Vec3<Real> colour = tracer.trace_eye_ray({x, y, near_z}, scratch);
            *out++ = to_byte(colour.x);
            *out++ = to_byte(colour.y);
            *out++ = to_byte(colour.z);
        }
    }
    return image;
}

template Image render<float>(const Scene&);
template Image render<double>(const Scene&);
template Image render<long double>(const Scene&);

}  // namespace rt
