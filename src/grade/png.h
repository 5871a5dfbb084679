// A small PNG encoder (8-bit RGB, no interlace, no row filters) for the grader's
// difference pictures; the image data is compressed by deflate_fixed() (deflate.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "raytracer/image.h"

namespace grade {

// The checksums PNG and zlib require; exposed for the tests.
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);
std::uint32_t adler32(const std::uint8_t* data, std::size_t size);

// The bytes of a PNG file holding the image (filter type 0 on every row).
std::vector<std::uint8_t> encode_png(const rt::Image& image);

// Writes encode_png(image) to the file. Returns an empty string on success, else why not.
std::string write_png(const std::string& file_name, const rt::Image& image);

}  // namespace grade
