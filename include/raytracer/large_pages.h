// Large arrays on 2 MiB pages where the system offers them (Linux's transparent huge
// pages, asked for with madvise): the first touch of a fresh 4 KiB page costs a fault.
//
// WHY: on this machine kind (a Firecracker guest) a fault costs 10-13 us, so reading and
// preparing random 100k (26 MB of text, 55 MB at its peak) spent most of its time in
// faults: 22,000 of them. The fix follows Embree's os_malloc() (common/sys/alloc.cpp),
// which asks for huge pages for its large blocks. Elsewhere this is a no-op.
#pragma once

#include <cstddef>
#include <limits>
#include <new>
#include <vector>

namespace rt {

// The memory of a large array: on Linux, a block of kLargeBlock bytes or more is mapped
// on its own, from a 2 MiB boundary, in whole 2 MiB pages, all of them advised (below
// it, elsewhere and under AddressSanitizer, it is operator new's). A block as malloc
// maps it starts a few bytes past a 4 KiB page: advice over it leaves its head up to the
// first boundary, and its tail, on 4 KiB pages, and a block of 2-4 MiB (random 100k's
// materials) holds no whole page to advise. On the EPYC guest, random 100k read and prepared
// (RES 1 1), whole process, 2 threads, medians of 11, three interleaved rounds: 3,400-
// 3,560 faults and 96-106 ms, on whole pages 661 faults and 71-77 ms, the same peak
// (50 MB).
inline constexpr std::size_t kLargeBlock = std::size_t{2} << 20;
void* allocate_large(std::size_t bytes);
void deallocate_large(void* block, std::size_t bytes) noexcept;
// Whether allocate_large() maps whole huge pages here (Linux, not under AddressSanitizer).
bool large_blocks_on_huge_pages();

// An allocator for arrays of millions of bytes that are filled once (a small file's
// text, the parsed spheres, the tree's build lists, nodes and leaf-ordered ellipsoids,
// the materials, the shadow hints): blocks from allocate_large().
template <typename T>
struct LargePages {
    using value_type = T;

    LargePages() noexcept = default;
    template <typename U>
    LargePages(const LargePages<U>& /*unused*/) noexcept {}  // NOLINT: implicit, as std::allocator's

    T* allocate(std::size_t n) {
        if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_large(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept { deallocate_large(p, n * sizeof(T)); }
    template <typename U>
    bool operator==(const LargePages<U>& /*unused*/) const noexcept {
        return true;
    }
    template <typename U>
    bool operator!=(const LargePages<U>& /*unused*/) const noexcept {
        return false;
    }
};

template <typename T>
using LargeVector = std::vector<T, LargePages<T>>;

}  // namespace rt
