// A bounding sphere of an ellipsoid (sphere_bounds.h; the screen bounds,
// screen_bounds.h, start from it), and a sphere as seen from a point (the light cones,
// light_cones.h).
#pragma once

#include <cmath>

namespace rt {

// A bounding sphere, in double (or wider) precision.
template <typename C>
struct BoundingSphere {
    C x, y, z, radius;
};

// A sphere as seen from a point: its distance, unit direction, and the sine and cosine
// of its angular radius; a sphere around the point (its radius widened by margin) or
// at a NaN distance is seen in every direction, and nothing else is set.
template <typename C>
struct SeenSphere {
    C distance, ux, uy, uz, sin_b, cos_b;
    bool everywhere;
};

template <typename C>
SeenSphere<C> seen_from(C px, C py, C pz, const BoundingSphere<C>& s, double margin) {
    using std::sqrt;
    SeenSphere<C> v{};
    const C wx = s.x - px, wy = s.y - py, wz = s.z - pz;
    v.distance = sqrt(wx * wx + wy * wy + wz * wz);
    v.everywhere = !(v.distance > s.radius * (C(1) + C(margin)));
    if (v.everywhere) return v;
    v.ux = wx / v.distance, v.uy = wy / v.distance, v.uz = wz / v.distance;
    v.sin_b = s.radius / v.distance;
    v.cos_b = sqrt(C(1) - v.sin_b * v.sin_b);
    return v;
}

}  // namespace rt
