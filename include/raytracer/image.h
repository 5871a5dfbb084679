// An 8-bit RGB image, rows from the top, and a colour's bytes (to_byte(), pixel_bytes()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

// An allocator whose resize() leaves new elements default-initialised (for bytes:
// unwritten) rather than zeroed.
//
// WHY: the renderer writes every byte of its rows anyway, and a zero fill beforehand
// costs the calling thread a page fault per 4 KiB of fresh memory. Unwritten, the pages
// of the renderer's row ring (row_ring.h) are first touched by the threads that render
// the rows, each on its own core.
template <typename T>
struct UninitializedAllocator : std::allocator<T> {
    template <typename U>
    struct rebind {
        using other = UninitializedAllocator<U>;
    };
    UninitializedAllocator() = default;
    template <typename U>
    explicit UninitializedAllocator(const UninitializedAllocator<U>& /*other*/) noexcept {}
    // Only the construction with no value is changed; copies construct as usual.
    template <typename U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
};

using Bytes = std::vector<std::uint8_t, UninitializedAllocator<std::uint8_t>>;

// A pixel's bytes: r, g, b (SPEC section 6).
constexpr std::size_t kBytesPerPixel = 3;
// The bytes of a block of pixels, `columns` wide and `rows` high (a row's: rows = 1).
constexpr std::size_t bytes_of_pixels(int columns, int rows = 1) {
    return static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows) * kBytesPerPixel;
}

struct Image {
    int width = 0, height = 0;
    Bytes rgb;  // bytes_of_pixels(width, height), top-left pixel first
};

// SPEC section 6: clamp to [0, 1], scale by 255, truncate. NaN gives 0.
//
// A level within rounding below a whole number is that number: BACK 0.6 is stored as
// 0.59999999999999997780, whose exact product with 255 is 152.99999999999999433. Double
// rounds it to 153, long double keeps it and truncates to 152, so the two renders would
// differ in every background pixel. The decimal scene means 153, so both give 153. The
// tolerance, 16 ulps of the scene's precision relative to the level, covers the rounding
// of a few products and sums of scene numbers (scene_precision.h); it is far below any
// real shading difference (keyIllum's three off-by-one pixels lie 1e-4 to 1e-3 below a step).
template <typename Real>
std::uint8_t to_byte(Real channel) {
    if (channel >= Real(1)) return 255;
    if (!(channel > Real(0))) return 0;
    const Real level = channel * Real(255);
    auto whole = static_cast<int>(level);
    if (Real(whole + 1) - level <= Real(16) * scene_epsilon<Real>() * level) ++whole;
    return static_cast<std::uint8_t>(whole);
}

// A colour's three bytes, to_byte() of each channel, into out[0..2].
template <typename Real>
void pixel_bytes(const Vec3<Real>& colour, std::uint8_t* out) {
    out[0] = to_byte(colour.x), out[1] = to_byte(colour.y), out[2] = to_byte(colour.z);
}

}  // namespace rt
