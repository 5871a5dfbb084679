// The scene as the file describes it: plain data, filled by the parser, read by the
// renderer. Numbers are kept in double whatever precision the renderer uses. The names
// of spheres and lights are read by the parser (its messages show them), not kept.
#pragma once

#include <string>
#include <vector>

#include "raytracer/large_pages.h"
#include "raytracer/vec3.h"

namespace rt {

using Colour = Vec3<double>;  // r, g, b as x, y, z

// A SPHERE statement: an ellipsoid (SPEC section 4), as the file gives it; the renderers
// take it as an Ellipsoid<Real> (reference/ellipsoid.h).
struct SphereSpec {
    Vec3<double> centre;
    Vec3<double> scale;  // the unit sphere is scaled by this, then moved to centre
    Colour colour;
    double ka = 0, kd = 0, ks = 0, kr = 0;
    double shininess = 0;  // the specular exponent n
    int line = 0;          // where it was declared, for messages
};

struct LightSpec {
    Vec3<double> position;
    Colour intensity;
    int line = 0;
};

struct Scene {
    double near_plane = 0, left = 0, right = 0, bottom = 0, top = 0;
    int columns = 0, rows = 0;
    LargeVector<SphereSpec> spheres;  // 100,000 take 12 MB
    std::vector<LightSpec> lights;
    Colour background;
    Colour ambient;
    std::string output;
    int output_line = 0;  // where OUTPUT was given, for messages about writing it
};

}  // namespace rt
