// Working memory that shares no cache line with any other allocation.
//
// WHY: a thread's working memory is written for every packet of rays, and an allocation
// made beside it in the heap (the scene's tables, another thread's working memory) can
// share its first or last cache line. Every write then takes that line from the other
// core, and the other thread's next read of its own data there waits for it: on the
// heavy scene the flat sweep's sphere culling took 8.7% of the samples on two threads
// against 5.4% on one, nearly all on such loads (perf), and its working memory on lines
// of its own took the whole process on two threads from 39.9 to 34.3 ms (perf stat,
// medians of 21, alternating runs).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <new>
#include <vector>

namespace rt {

// An allocator whose blocks start on a cache line and fill whole lines.
template <typename T>
struct OwnCacheLines {
    using value_type = T;
    // A line here is 128 bytes: x86-64 cores fetch 64-byte lines in pairs (the
    // adjacent-line prefetcher), and Apple's ARM cores have 128-byte lines (C++17's
    // hardware_destructive_interference_size is not in every standard library).
    static constexpr std::size_t kLine = 128;
    static constexpr std::size_t kAlign = std::max(kLine, alignof(T));

    OwnCacheLines() noexcept = default;
    template <typename U>
    OwnCacheLines(const OwnCacheLines<U>& /*unused*/) noexcept {}  // NOLINT: implicit, as std::allocator's

    T* allocate(std::size_t n) {
        // n * sizeof(T) rounded up to whole lines must not wrap around (a vector's own
        // limit need not be that tight: MSVC's counts elements only).
        if (n > (std::numeric_limits<std::size_t>::max() - (kAlign - 1)) / sizeof(T))
            throw std::bad_array_new_length();
        const std::size_t bytes = (n * sizeof(T) + kAlign - 1) / kAlign * kAlign;
        return static_cast<T*>(::operator new (bytes, std::align_val_t{kAlign}));
    }
    void deallocate(T* p, std::size_t /*n*/) noexcept { ::operator delete (p, std::align_val_t{kAlign}); }
    template <typename U>
    bool operator==(const OwnCacheLines<U>& /*unused*/) const noexcept {
        return true;
    }
    template <typename U>
    bool operator!=(const OwnCacheLines<U>& /*unused*/) const noexcept {
        return false;
    }
};

template <typename T>
using OwnLinesVector = std::vector<T, OwnCacheLines<T>>;

}  // namespace rt
