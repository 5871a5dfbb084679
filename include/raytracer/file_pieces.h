// A large scene file read in pieces on the helper threads (load_scene.cpp).
//
// WHY: reading random 100k's 26 MB took 21 ms on one thread, nearly all of it the first
// touch of the fresh pages the bytes are copied into (about 2 us a page here); two
// threads copying a piece each take 10 ms.
#pragma once

#include <cstddef>
#include <cstdio>

namespace rt {

// Whether read_in_pieces() can read at an offset of its own on this system: positioned
// reads (pread) on POSIX; on Windows the caller reads the file as a stream.
#ifdef _WIN32
inline constexpr bool kReadsInPieces = false;
#else
inline constexpr bool kReadsInPieces = true;
#endif

// The `size` bytes of the file open as `in` into bytes, one piece per thread, each taken
// by whichever thread is free, all from that one handle (so from that one file, even
// where another is renamed over its name meanwhile) by reads at an offset, which leave
// its position where it was. False where the file does not hold exactly `size` bytes
// (it changed since its size was taken), where a read fails, and where !kReadsInPieces.
bool read_in_pieces(std::FILE* in, std::size_t size, unsigned threads, char* bytes);

}  // namespace rt
