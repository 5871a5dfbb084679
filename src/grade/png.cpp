#include "png.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

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

// A zlib stream (RFC 1950) of stored deflate blocks (RFC 1951 section 3.2.4), each at most
// 65535 bytes; the last carries BFINAL.
std::vector<std::uint8_t> zlib_stored(const std::vector<std::uint8_t>& raw) {
    constexpr std::size_t kMaxBlock = 65535;
    std::vector<std::uint8_t> out = {0x78, 0x01};  // deflate, 32 KiB window, no dictionary
    std::size_t at = 0;
    do {
        const std::size_t size = std::min(kMaxBlock, raw.size() - at);
        const bool last = at + size == raw.size();
        out.push_back(last ? 1 : 0);
        const auto length = static_cast<std::uint16_t>(size);
        const auto complement = static_cast<std::uint16_t>(~length);
        for (const std::uint16_t v : {length, complement}) {
            out.push_back(static_cast<std::uint8_t>(v & 0xFFU));
            out.push_back(static_cast<std::uint8_t>(v >> 8U));
        }
        out.insert(out.end(), raw.begin() + static_cast<std::ptrdiff_t>(at),
                   raw.begin() + static_cast<std::ptrdiff_t>(at + size));
        at += size;
    } while (at < raw.size());
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
    put_chunk(png, "IDAT", zlib_stored(raw));
    put_chunk(png, "IEND", {});
    return png;
}

std::string write_png(const std::string& file_name, const rt::Image& image) {
    const std::vector<std::uint8_t> bytes = encode_png(image);
    std::ofstream out(std::filesystem::u8path(file_name), std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) return "cannot write '" + file_name + "'";
    return {};
}

}  // namespace grade
