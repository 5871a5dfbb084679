// A small deflate compressor (RFC 1951) for the PNG encoder: one block of the fixed
// Huffman codes, whose matches are looked for at a few given distances only. For a PNG's
// rows those are the pixel to the left and the pixel above, which is where a rendered
// image repeats itself: a flat background or a smooth shade compresses 20- to 100-fold,
// with no hash tables and no dynamic code tables to get wrong.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace grade {

// The deflate stream of data (no zlib wrapper), trying a back-reference at each of the
// distances (each from 1 to 32768).
std::vector<std::uint8_t> deflate_fixed(const std::vector<std::uint8_t>& data,
                                        const std::vector<std::size_t>& distances);

}  // namespace grade
