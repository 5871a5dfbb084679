#include "png.h"

#include <array>

#include "deflate.h"
#include "raytracer/output_file.h"

namespace grade {
namespace {

// The table of the reflected CRC-32 of polynomial 0xEDB88320, as the PNG specification gives it.
std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1U) ? 0xEDB88320U ^ (c >> 1U) : c >> 1U;
        table[n] = c;
    }
    return table;
}

void put_u32_big_endian(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(value >> shift));
}

// A chunk: length, type, data, and the CRC of type and data.
void put_chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
    put_u32_big_endian(out, static_cast<std::uint32_t>(data.size()));
    const std::size_t type_at = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    put_u32_big_endian(out, crc32(out.data() + type_at, out.size() - type_at));
}

// A zlib stream (RFC 1950): header, deflate data, Adler-32 of the uncompressed bytes.
std::vector<std::uint8_t> zlib_stream(const std::vector<std::uint8_t>& raw, std::size_t row_bytes) {
    std::vector<std::uint8_t> out = {0x78, 0x01};  // deflate, 32 KiB window, no dictionary
    // Matches with the pixel to the left and the one above (rows are filter byte + pixels).
    std::vector<std::size_t> distances = {3};
    if (row_bytes <= 32768) distances.push_back(row_bytes);
    const std::vector<std::uint8_t> compressed = deflate_fixed(raw, distances);
    out.insert(out.end(), compressed.begin(), compressed.end());
    put_u32_big_endian(out, adler32(raw.data(), raw.size()));
    return out;
}

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
    static const std::array<std::uint32_t, 256> table = make_crc_table();
    std::uint32_t c = crc ^ 0xFFFFFFFFU;
    for (std::size_t i = 0; i < size; ++i) c = table[(c ^ data[i]) & 0xFFU] ^ (c >> 8U);
    return c ^ 0xFFFFFFFFU;
}

std::uint32_t adler32(const std::uint8_t* data, std::size_t size) {
    constexpr std::uint32_t kModulus = 65521;
    std::uint32_t a = 1, b = 0;
    for (std::size_t i = 0; i < size; ++i) {
        a = (a + data[i]) % kModulus;
        b = (b + a) % kModulus;
    }
    return (b << 16U) | a;
}

std::vector<std::uint8_t> encode_png(const rt::Image& image) {
    const auto width = static_cast<std::size_t>(image.width), height = static_cast<std::size_t>(image.height);
    std::vector<std::uint8_t> raw;  // each row: its filter type (0, none), then its pixels
    raw.reserve(height * (1 + 3 * width));
    for (std::size_t row = 0; row < height; ++row) {
        raw.push_back(0);
        const auto begin = image.rgb.begin() + static_cast<std::ptrdiff_t>(row * 3 * width);
        raw.insert(raw.end(), begin, begin + static_cast<std::ptrdiff_t>(3 * width));
    }
    std::vector<std::uint8_t> header;
    put_u32_big_endian(header, static_cast<std::uint32_t>(width));
    put_u32_big_endian(header, static_cast<std::uint32_t>(height));
    header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, filters, no interlace

    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    put_chunk(png, "IHDR", header);
    put_chunk(png, "IDAT", zlib_stream(raw, 1 + 3 * width));
    put_chunk(png, "IEND", {});
    return png;
}

std::string write_png(const std::string& file_name, const rt::Image& image) {
    const std::vector<std::uint8_t> bytes = encode_png(image);
    return rt::write_whole_file(file_name.c_str(), bytes.data(), bytes.size());
}

}  // namespace grade
