// Large arrays on huge pages (large_pages.h): a LargeVector holds what a vector holds,
// and, where Linux offers transparent huge pages for advised memory, one filled once is
// backed by them from end to end.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "check.h"
#include "raytracer/large_pages.h"

namespace {

// The "AnonHugePages" kilobytes of the mapping that holds address, from
// /proc/self/smaps; -1 where that cannot be read (not Linux).
long huge_kib_at(const void* address) {
    std::ifstream smaps("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(address);
    bool inside = false;
    for (std::string line; std::getline(smaps, line);) {
        std::uintptr_t first = 0, last = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> first >> dash >> last && dash == '-') {
            inside = first <= at && at < last;
        } else if (inside && line.rfind("AnonHugePages:", 0) == 0) {
            return std::stol(line.substr(14));
        }
    }
    return -1;
}

// Whether the kernel backs memory advised MADV_HUGEPAGE with huge pages
// ("always" or "madvise" is the mode in brackets).
bool huge_pages_on_advice() {
    std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string text;
    std::getline(mode, text);
    return text.find("[always]") != std::string::npos || text.find("[madvise]") != std::string::npos;
}

}  // namespace

TEST(a_large_vector_keeps_its_contents_as_it_grows) {
    rt::LargeVector<std::uint64_t> v = {1, 2, 3};
    v.reserve(std::size_t{3} << 20);  // 24 MiB
    CHECK(v.capacity() >= (std::size_t{3} << 20));
    CHECK_EQ(v.size(), std::size_t{3});
    CHECK(v[0] == 1 && v[1] == 2 && v[2] == 3);
    for (std::uint64_t k = 3; k < (std::uint64_t{5} << 20); ++k) v.push_back(k + 1);  // past the reserve
    std::uint64_t wrong = 0;
    for (std::size_t k = 0; k < v.size(); ++k) wrong += v[k] != k + 1;
    CHECK_EQ(wrong, std::uint64_t{0});
    rt::LargeVector<char> small(100, 'x');  // below rt::kLargeBlock: operator new's
    CHECK_EQ(small[99], 'x');
}

TEST(an_empty_large_vector_holds_nothing) {
    rt::LargeVector<char> empty;
    empty.reserve(0);
    CHECK(empty.empty());
    rt::LargeVector<char> emptied(rt::kLargeBlock, 'x');  // whole pages, then given back
    rt::LargeVector<char>().swap(emptied);
    CHECK(emptied.empty());
}

// From its first byte to its last: a block that started a few bytes past a 4 KiB page
// had its head and tail on small pages (a block of 2 MiB and a bit, none on huge ones).
TEST(a_large_vector_filled_once_is_on_huge_pages_from_end_to_end) {
    rt::LargeVector<char> v;
    v.reserve(rt::kLargeBlock + 12345);
    v.assign(v.capacity(), 'x');
    const long kib = huge_kib_at(v.data());  // of the block's mapping
    if (kib < 0 || !huge_pages_on_advice() || !rt::large_blocks_on_huge_pages()) {
        std::printf("no transparent huge pages here: not checked\n");
        return;
    }
    CHECK_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % (std::uintptr_t{2} << 20), std::uintptr_t{0});
    CHECK(kib >= 2L * 2048);  // both of its pages, the first and the one that holds its tail
}
