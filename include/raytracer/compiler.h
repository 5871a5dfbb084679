// Hints to the compiler, with their portable fallback.
#pragma once

// Forces inlining where GCC's heuristics flip with unrelated edits (measured: the
// shadow test called out of line costs the heavy scene 4 % more instructions).
#if defined(__GNUC__) || defined(__clang__)
#define RT_ALWAYS_INLINE __attribute__((always_inline)) inline
#elif defined(_MSC_VER)
#define RT_ALWAYS_INLINE __forceinline
#else
#define RT_ALWAYS_INLINE inline
#endif

// Placed before a short loop over the lanes of a packet that GCC should vectorise: GCC
// otherwise unrolls such a loop completely before its vectoriser runs, and its
// basic-block vectoriser does not take the unrolled reductions (measured: lane masks
// packed into bits cost 50 scalar instructions instead of a few vector ones).
#if defined(__GNUC__) && !defined(__clang__)
#define RT_VECTOR_LOOP _Pragma("GCC unroll 1")
#else
#define RT_VECTOR_LOOP
#endif
