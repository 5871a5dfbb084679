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

// Placed before a loop that GCC must vectorise; the test build.vectorised_loops fails
// where GCC's report does not list it as vectorised. On a short loop over the lanes of
// a packet it also keeps GCC from unrolling the loop completely before its vectoriser
// runs, as its basic-block vectoriser does not take the unrolled reductions (measured:
// lane masks packed into bits cost 50 scalar instructions instead of a few vector ones).
#if defined(__GNUC__) && !defined(__clang__)
#define RT_VECTOR_LOOP _Pragma("GCC unroll 1")
#else
#define RT_VECTOR_LOOP
#endif

// Defined where AddressSanitizer instruments the build (GCC's macro, Clang's feature
// test): the sanitizers map terabytes of address space, and their checks cover only
// memory from the heap.
#if defined(__SANITIZE_ADDRESS__)
#define RT_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RT_UNDER_ASAN 1
#endif
#endif
// Likewise for ThreadSanitizer, which maps terabytes too, and runs a thread of its own.
#if defined(__SANITIZE_THREAD__)
#define RT_UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define RT_UNDER_TSAN 1
#endif
#endif
// Under either, no address-space limit (RLIMIT_AS) can be set: they map terabytes.
#if defined(RT_UNDER_ASAN) || defined(RT_UNDER_TSAN)
#define RT_SANITIZER_MAPS_TERABYTES 1
#endif

// Whether Lanes (lanes.h) are held as native 32-byte vectors: where the compiler has
// vector extensions (GCC, Clang) and the target AVX.
#if (defined(__GNUC__) || defined(__clang__)) && defined(__AVX__)
#define RT_NATIVE_LANES 1
#else
#define RT_NATIVE_LANES 0
#endif
