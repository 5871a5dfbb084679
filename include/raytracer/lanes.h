// Lanes<Real, N>: N numbers, one per ray, with a scalar's arithmetic done lane by lane,
// so that one piece of shading code (shading.h) runs for one ray (T = double) or for
// the lanes of a register at a time (T = Lanes<double, kRegisterLanes>, a tile's or a
// packet's) and gives each lane the scalar's bits.
//
// Each operator is a vector instruction per 32 bytes of lanes (4 doubles in an AVX
// register; detail::NativeVector below), or a loop over the lanes that the compiler
// vectorises; a lane's value is the scalar operation on that lane's operands, rounded as
// a scalar one (IEEE operations, no fused multiply-adds: CMakeLists.txt). Native vectors
// of 64 bytes (AVX-512) measured 15% slower on the tree's tiles than 32.
//
// A comparison gives a mask, bit k for lane k; where code for one ray branches, code
// over lanes selects (select(), any(): masks.h has their one-ray forms), so a lane never
// gets a term its scalar run would have skipped, and never an addition of zero in its
// place.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "raytracer/compiler.h"
#include "raytracer/reference/masks.h"
#include "raytracer/vec3.h"

namespace rt {

// The lanes' bits of an N-lane set, bit k for lane k, as a constant table: selects of
// these rather than shifts by k let GCC vectorise the loops that build sets.
template <int N>
struct LaneBitTable {
    LaneBits bit[N];
};
template <int N>
constexpr LaneBitTable<N> make_lane_bits() {
    static_assert(N <= 64, "one bit per lane");
    LaneBitTable<N> table{};
    for (int k = 0; k < N; ++k) table.bit[k] = LaneBits(1) << k;
    return table;
}
template <int N>
inline constexpr LaneBitTable<N> kLaneBits = make_lane_bits<N>();

// Where the compiler has vector extensions (GCC, Clang) and the target AVX, a Lanes of
// float, double or int32 is held as 32-byte native vectors, which the compiler keeps in
// registers from one operation to the next, where it stores and loads an array's lanes
// around each (the tree's tiles, rendering alone: testSample 20% and the heavy scene 22%
// faster). Elsewhere (MSVC; SSE-only targets, which pass no 32-byte vector in registers)
// an array.
namespace detail {
template <typename E>
struct NativeVector;
#if RT_NATIVE_LANES
template <typename Real>
inline constexpr bool kNativeLanes =
    std::is_same_v<Real, double> || std::is_same_v<Real, float> || std::is_same_v<Real, std::int32_t>;
template <typename E>
struct NativeVector {
    // NOLINTNEXTLINE(modernize-use-using): GCC takes a vector_size of a template's type only on a typedef
    typedef E type __attribute__((vector_size(32)));
};
// A comparison's mask (-1 or 0 in each lane) as bits, bit i for lane i: one instruction,
// vmovmskpd or vmovmskps, through the builtin that GCC's and Clang's _mm256_movemask_pd()
// and _mm256_movemask_ps() call. Not through <immintrin.h>: its 53,000 lines were more
// than half of each render unit's preprocessed source, 0.3-0.5 s of its 4.4-4.9 s build.
template <typename Mask>
RT_ALWAYS_INLINE unsigned bits_of(Mask m) {
    // The casts reinterpret the mask's 32 bytes, as _mm256_movemask_pd()'s own.
    if constexpr (sizeof(m[0]) == 8)
        return static_cast<unsigned>(__builtin_ia32_movmskpd256((NativeVector<double>::type)m));
    return static_cast<unsigned>(__builtin_ia32_movmskps256((NativeVector<float>::type)m));
}
// The mask whose lane i is -1 where bit i of bits is set, else 0.
template <typename Mask>
RT_ALWAYS_INLINE Mask mask_of(unsigned bits) {
    using E = std::remove_reference_t<decltype(Mask{}[0])>;
    Mask lane_bit;
    for (int i = 0; i < int(sizeof(Mask) / sizeof(E)); ++i) lane_bit[i] = E(1) << i;
    return ((Mask{} + static_cast<E>(bits)) & lane_bit) != 0;
}
#else
template <typename Real>
inline constexpr bool kNativeLanes = false;
template <typename Mask>
unsigned bits_of(Mask m);  // named in Lanes' native branches, which are not instantiated here
template <typename Mask>
Mask mask_of(unsigned bits);
#endif
// A Lanes' numbers: an array, and where kNative the same bytes as native vectors.
template <typename Real, int N, bool kNative>
union LaneStorage {
    Real lane[N];
};
template <typename Real, int N>
union LaneStorage<Real, N, true> {  // GCC and Clang define reading the other member of a union
    typename NativeVector<Real>::type part[N * sizeof(Real) / 32];
    Real lane[N];
};
}  // namespace detail

template <typename Real, int N>
struct Lanes {
    static constexpr int kPart = 32 / sizeof(Real);  // lanes in a native vector
    static constexpr bool kNative = detail::kNativeLanes<Real> && N % kPart == 0;
    detail::LaneStorage<Real, N, kNative> v;

    Lanes() = default;
    // A constant, the same in every lane: T(1) in code written for T = Real or Lanes.
    RT_ALWAYS_INLINE Lanes(Real x) {  // implicit, as a scalar converts to a wider one
        if constexpr (kNative) {
            typename detail::NativeVector<Real>::type p;
            for (int i = 0; i < kPart; ++i) p[i] = x;
            for (auto& q : v.part) q = p;
        } else {
            RT_VECTOR_LOOP
            for (int k = 0; k < N; ++k) v.lane[k] = x;
        }
    }
    Real& operator[](int k) { return v.lane[k]; }
    const Real& operator[](int k) const { return v.lane[k]; }
    const Real* data() const { return v.lane; }  // the N lanes in order, for code over arrays
    static Lanes load(const Real* from) {        // and from N numbers in order
        Lanes r;
        std::memcpy(r.v.lane, from, sizeof r.v.lane);
        return r;
    }

    // Lane by lane: r[k] = op(a[k], b[k]) (op takes both lanes and native vectors).
    template <typename Op>
    RT_ALWAYS_INLINE static Lanes map(const Lanes& a, const Lanes& b, Op op) {
        Lanes r;
        if constexpr (kNative) {
            for (int j = 0; j < N / kPart; ++j) r.v.part[j] = op(a.v.part[j], b.v.part[j]);
        } else {
            RT_VECTOR_LOOP
            for (int k = 0; k < N; ++k) r.v.lane[k] = op(a.v.lane[k], b.v.lane[k]);
        }
        return r;
    }
    // The lanes where a[k] op b[k] holds, as bits.
    template <typename Op>
    RT_ALWAYS_INLINE static LaneBits where(const Lanes& a, const Lanes& b, Op op) {
        LaneBits set = 0;
        if constexpr (kNative) {
            for (int j = 0; j < N / kPart; ++j)
                set |= LaneBits{detail::bits_of(op(a.v.part[j], b.v.part[j]))} << (j * kPart);
        } else {
            RT_VECTOR_LOOP
            for (int k = 0; k < N; ++k) set |= op(a.v.lane[k], b.v.lane[k]) ? kLaneBits<N>.bit[k] : 0;
        }
        return set;
    }

    RT_ALWAYS_INLINE friend Lanes operator+(const Lanes& a, const Lanes& b) {
        return map(a, b, [](auto x, auto y) { return x + y; });
    }
    RT_ALWAYS_INLINE friend Lanes operator-(const Lanes& a, const Lanes& b) {
        return map(a, b, [](auto x, auto y) { return x - y; });
    }
    RT_ALWAYS_INLINE friend Lanes operator*(const Lanes& a, const Lanes& b) {
        return map(a, b, [](auto x, auto y) { return x * y; });
    }
    RT_ALWAYS_INLINE friend Lanes operator/(const Lanes& a, const Lanes& b) {
        return map(a, b, [](auto x, auto y) { return x / y; });
    }
    RT_ALWAYS_INLINE friend Lanes operator&(const Lanes& a, const Lanes& b) {
        return map(a, b, [](auto x, auto y) { return x & y; });
    }
    RT_ALWAYS_INLINE friend Lanes operator-(const Lanes& a) {
        return map(a, a, [](auto x, auto) { return -x; });
    }
    RT_ALWAYS_INLINE friend Lanes operator>>(const Lanes& a, int s) {
        return map(a, a, [s](auto x, auto) { return x >> s; });
    }

    RT_ALWAYS_INLINE friend LaneBits operator>(const Lanes& a, const Lanes& b) {
        return where(a, b, [](auto x, auto y) { return x > y; });
    }
    RT_ALWAYS_INLINE friend LaneBits operator>=(const Lanes& a, const Lanes& b) {
        return where(a, b, [](auto x, auto y) { return x >= y; });
    }
    RT_ALWAYS_INLINE friend LaneBits operator<(const Lanes& a, const Lanes& b) {
        return where(a, b, [](auto x, auto y) { return x < y; });
    }
    RT_ALWAYS_INLINE friend LaneBits operator!=(const Lanes& a, const Lanes& b) {
        return where(a, b, [](auto x, auto y) { return x != y; });
    }

    RT_ALWAYS_INLINE friend Lanes sqrt(const Lanes& a) {
        using std::sqrt;
        Lanes r;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) r.v.lane[k] = sqrt(a.v.lane[k]);
        return r;
    }
    RT_ALWAYS_INLINE friend Lanes abs(const Lanes& a) {
        using std::abs;
        Lanes r;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) r.v.lane[k] = abs(a.v.lane[k]);
        return r;
    }
    // std::pow in each lane of where (the others are 0): pow() has no vector form.
    RT_ALWAYS_INLINE friend Lanes pow_where(LaneBits where, const Lanes& x, const Lanes& n) {
        using std::pow;
        Lanes r(Real(0));
        for (int k = 0; k < N; ++k)
            if ((where >> k) & 1U) r.v.lane[k] = pow(x.v.lane[k], n.v.lane[k]);
        return r;
    }
    // The same choice for every lane (a mask of one ray).
    RT_ALWAYS_INLINE friend Lanes select(bool where, const Lanes& a, const Lanes& b) { return where ? a : b; }
    // r[k] = bit k of where ? a[k] : b[k].
    RT_ALWAYS_INLINE friend Lanes select(LaneBits where, const Lanes& a, const Lanes& b) {
        Lanes r;
        if constexpr (kNative) {
            using Mask = decltype(a.v.part[0] != b.v.part[0]);
            for (int j = 0; j < N / kPart; ++j)
                r.v.part[j] = detail::mask_of<Mask>(static_cast<unsigned>(where >> (j * kPart)))
                                  ? a.v.part[j]
                                  : b.v.part[j];
        } else {
            RT_VECTOR_LOOP
            for (int k = 0; k < N; ++k)
                r.v.lane[k] = (where & kLaneBits<N>.bit[k]) != 0 ? a.v.lane[k] : b.v.lane[k];
        }
        return r;
    }
};

// Lane k of a Vec3 of lanes, and setting it.
template <typename Real, int N>
Vec3<Real> lane(const Vec3<Lanes<Real, N>>& v, int k) {
    return {v.x[k], v.y[k], v.z[k]};
}
template <typename Real, int N>
void set_lane(Vec3<Lanes<Real, N>>& v, int k, const Vec3<Real>& value) {
    v.x[k] = value.x, v.y[k] = value.y, v.z[k] = value.z;
}

// The lanes of one 32-byte vector register (4 doubles, 8 floats), at most N: code over
// more lanes at once keeps its chains in memory rather than registers (shading.h over
// the 16 lanes of a tile: 3-7% slower than a register at a time; over two registers,
// 64 bytes, the same for the tiles and up to 4% slower for the flat sweep's packets).
template <typename Real, int N>
inline constexpr int kRegisterLanes = std::min(N, std::max(1, 32 / int(sizeof(Real))));

// Lanes [first, first + M) of a lane set, as lanes 0 to M - 1 (a register's chunk of
// a tile's or a packet's lanes).
template <int M>
LaneBits lanes_from(LaneBits set, int first) {
    static_assert(M >= 1 && M < 64, "a part of a set");
    return (set >> first) & ((LaneBits(1) << M) - 1);
}

// The integers that go with lanes (masks.h): a whole exponent per lane.
template <typename Real, int N>
struct IntegerOfT<Lanes<Real, N>> {
    using type = Lanes<std::int32_t, N>;
};

}  // namespace rt
