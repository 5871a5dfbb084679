// The scene's lengths brought near 1 by one power of two, where they lie so far from it
// that their squares would overflow or underflow: raytracer.exe does it to every scene
// it reads, before rendering; the renderers take a scene as it is.
//
// WHY: shading normalises vectors of the scene's size (a normal (P - C)/s^2, the way to
// a light L - P) through their squared length, which overflows past about 1e154 and
// underflows below about 1e-154: a scene drawn at 1e160 lost its lighting, and LEFT
// -1e308 RIGHT 1e308 made every eye ray infinite. Multiplying every length (the window,
// the centres, the scales, the lights) by 2^k is exact while nothing overflows, and
// every ray parameter t, normal and direction of light is then what it was (the
// metamorphic tests check this on every hard and course scene), so the image is the
// one exact arithmetic gives for the scene as written. Colours, coefficients and
// intensities have no unit and stay as they are.
#pragma once

#include "raytracer/scene.h"

namespace rt {

// Lengths between 2^-kLengthExponentRange and 2^kLengthExponentRange render as they
// are (every course and scale scene; no copy of the scene).
inline constexpr int kLengthExponentRange = 100;

// The k of 2^k that centres the scene's nonzero lengths on 1 (the exponents of the
// least and the greatest, averaged), or 0 where they all lie within the range above, or
// where they span more than 2^-1000 to 2^1000 (nothing can hold both ends).
int length_shift(const Scene& scene);

// Every length of the scene multiplied by 2^shift.
void scale_lengths(Scene& scene, int shift);

// scale_lengths() by length_shift(): the scene as raytracer.exe renders it.
inline void bring_lengths_near_one(Scene& scene) {
    if (const int shift = length_shift(scene); shift != 0) scale_lengths(scene, shift);
}

}  // namespace rt
