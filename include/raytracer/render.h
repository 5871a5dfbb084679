// Renders a scene to an image: one eye ray per pixel through the pixel's top-left
// corner on the near plane (SPEC section 3), traced in the scalar type Real.
#pragma once

#include "raytracer/image.h"
#include "raytracer/scene.h"

namespace rt {

// Instantiated for float, double and long double (src/render.cpp).
template <typename Real>
Image render(const Scene& scene);

}  // namespace rt
