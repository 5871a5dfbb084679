// Large arrays on 2 MiB pages where the system offers them (Linux's transparent huge
// pages, asked for with madvise): the first touch of a fresh 4 KiB page costs a fault.
//
// WHY: on this machine kind (a Firecracker guest) a fault costs 10-13 us, so reading and
// preparing random 100k (26 MB of text, 55 MB at its peak) spent most of its time in
// faults: 22,000 of them. The fix follows Embree's os_malloc() (common/sys/alloc.cpp),
// which asks for huge pages for its large blocks. Elsewhere this is a no-op.
#pragma once

#include <cstddef>
#include <vector>

namespace rt {

// Asks that the whole 2 MiB pages inside [data, data + bytes) be backed by huge pages
// when first touched. Only advice: harmless on memory already touched, and a no-op where
// the range holds fewer than two, where it cannot pay.
void advise_large_pages(void* data, std::size_t bytes);

// v.reserve(n), the reserved memory advised as above: for arrays of millions of bytes
// that are then filled once.
template <typename T>
void reserve_large(std::vector<T>& v, std::size_t n) {
    v.reserve(n);
    advise_large_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace rt
