// What every scene that parse_scene accepts must satisfy (SPEC section 2). The fuzz
// harnesses abort when it does not, so that libFuzzer records the input as a crash.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>

#include "raytracer/parser.h"
#include "raytracer/scene.h"

namespace fuzz {

inline void require(bool condition) {
    if (!condition) std::abort();
}

inline bool finite(const rt::Vec3<double>& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline void check_accepted(const rt::Scene& s) {
    require(std::isfinite(s.near_plane) && s.near_plane > 0);
    require(std::isfinite(s.left) && std::isfinite(s.right) && s.left < s.right);
    require(std::isfinite(s.bottom) && std::isfinite(s.top) && s.bottom < s.top);
    require(s.columns > 0 && s.rows > 0 && s.columns <= rt::kMaxImageSide && s.rows <= rt::kMaxImageSide);
    require(static_cast<long long>(s.columns) * s.rows <= rt::kMaxImagePixels);
    require(finite(s.background) && finite(s.ambient) && !s.output.empty() && s.output_line > 0);
    for (const rt::SphereSpec& sphere : s.spheres) {
        require(finite(sphere.centre) && finite(sphere.scale) && finite(sphere.colour));
        require(sphere.scale.x != 0 && sphere.scale.y != 0 && sphere.scale.z != 0);
        require(std::isfinite(sphere.ka) && std::isfinite(sphere.kd) && std::isfinite(sphere.ks) &&
                std::isfinite(sphere.kr) && std::isfinite(sphere.shininess));
    }
    for (const rt::LightSpec& light : s.lights) require(finite(light.position) && finite(light.intensity));
}

// A refusal is one line that names the file: "<file>[:<line>]: error: ...".
inline void check_refusal(const std::string& message, const std::string& file) {
    require(message.rfind(file + ":", 0) == 0);
    require(message.find(": error: ") != std::string::npos);
    require(message.find('\n') == std::string::npos && message.find('\r') == std::string::npos);
}

}  // namespace fuzz
