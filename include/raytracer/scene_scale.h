// The scene's lengths brought near 1 by one power of two, where they lie so far from it
// that their squares would overflow or underflow: raytracer.exe does it to every scene
// it reads, before rendering; the renderers take a scene as it is.
//
// WHY: shading normalises vectors of the scene's size (a normal (P - C)/s^2, the way to
// a light L - P) through their squared length, which overflows past about 1e154 and
// underflows below about 1e-154: a scene drawn at 1e160 would lose its lighting, and
// LEFT -1e308 RIGHT 1e308 would make every eye ray infinite. Multiplying every length
// (the window, the centres, the scales, the lights) by 2^k is exact while nothing
// overflows, and every ray parameter t, normal and direction of light is then what it
// was (the metamorphic tests check this on every hard and course scene), so the image is
// the one exact arithmetic gives for the scene as written. Colours, coefficients and
// intensities have no unit and stay as they are.
#pragma once

#include "raytracer/scene.h"

namespace rt {

// Calls f with every length of the scene (NEAR, the window's edges, the centres, the
// scales, the lights), in place where scene is not const: the one list of what a
// length is, for the shift below and for the tests that scale a scene.
template <typename SceneType, typename F>
void for_each_length(SceneType& scene, F f) {
    for (auto* x : {&scene.near_plane, &scene.left, &scene.right, &scene.bottom, &scene.top}) f(*x);
    auto each = [&f](auto& v) { f(v.x), f(v.y), f(v.z); };
    for (auto& s : scene.spheres) each(s.centre), each(s.scale);
    for (auto& l : scene.lights) each(l.position);
}

// Sizes (NEAR, the window's width and height, the scales) and coordinates (the window's
// edges, the centres, the lights) between 2^-kLengthExponentRange and
// 2^kLengthExponentRange render as they are (every course and scale scene; no copy).
// A coordinate far below the scene's size is not held to that range: it only ever
// enters a difference, and shifted below the smallest double it becomes 0, a move far
// below any rounding of the scene.
inline constexpr int kLengthExponentRange = 100;

// How far from 2^0 a shift may take the least size and the greatest length: their
// squares then stay finite and normal (2^+-1000 within 2^+-1022).
inline constexpr int kLengthExponentLimit = 500;

// The k of 2^k that centres the scene's least size and greatest length on 1 (their
// exponents averaged, the result rounded down, so that a scene and the same scene times
// 2^m end on the same numbers), or 0 where they lie within the range above. Where
// centring would take an end past 2^+-kLengthExponentLimit, the shift stops there; where
// they span more than twice that, the greatest is held at 2^kLengthExponentLimit (a far
// light loses no light; a size far below the rest loses its own shading's precision);
// past three times that (a size would become 0) the scene stays as written.
int length_shift(const Scene& scene);

// Every length of the scene multiplied by 2^shift.
void scale_lengths(Scene& scene, int shift);

// scale_lengths() by length_shift(): the scene as raytracer.exe renders it.
inline void bring_lengths_near_one(Scene& scene) {
    if (const int shift = length_shift(scene); shift != 0) scale_lengths(scene, shift);
}

}  // namespace rt
