// The grader's PNG encoder, decoded back by an independent reader written here from the
// PNG, zlib and deflate specifications (stored and fixed-Huffman blocks, the encoder's
// kind): signature, chunk CRCs, IHDR fields, the zlib header and Adler-32, every row's
// filter byte, and the pixels themselves.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "../check.h"
#include "png.h"

namespace {

using Bytes = std::vector<std::uint8_t>;

std::uint32_t big_endian_at(const Bytes& b, std::size_t at) {
    return (std::uint32_t{b[at]} << 24U) | (std::uint32_t{b[at + 1]} << 16U) |
           (std::uint32_t{b[at + 2]} << 8U) | std::uint32_t{b[at + 3]};
}

// Reads bits least significant first, as deflate stores them.
struct BitReader {
    const Bytes& data;
    std::size_t bit = 0;
    bool overrun = false;
    unsigned bits(int n) {
        unsigned value = 0;
        for (int i = 0; i < n; ++i, ++bit) {
            if (bit / 8 >= data.size()) {
                overrun = true;
                return 0;
            }
            value |= ((data[bit / 8] >> (bit % 8)) & 1U) << i;
        }
        return value;
    }
    unsigned code(int n) {  // a Huffman code: most significant bit first
        unsigned value = 0;
        for (int i = 0; i < n; ++i) value = (value << 1U) | bits(1);
        return value;
    }
    // The fixed literal/length code (RFC 1951 section 3.2.6): 7, 8 or 9 bits.
    unsigned symbol() {
        unsigned c = code(7);
        if (c <= 0x17) return 256 + c;
        c = (c << 1U) | bits(1);
        if (c >= 0x30 && c <= 0xBF) return c - 0x30;
        if (c >= 0xC0 && c <= 0xC7) return 280 + c - 0xC0;
        c = (c << 1U) | bits(1);
        return 144 + c - 0x190;
    }
};

// One fixed-Huffman block into out; false on a code that cannot occur.
bool inflate_fixed_block(BitReader& in, Bytes& out) {
    static const unsigned kLengthBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                             31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const int kLengthExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                         2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    for (;;) {
        const unsigned s = in.symbol();
        if (in.overrun || s > 285) return false;
        if (s < 256) {
            out.push_back(static_cast<std::uint8_t>(s));
            continue;
        }
        if (s == 256) return true;
        const unsigned length = kLengthBase[s - 257] + in.bits(kLengthExtra[s - 257]);
        const unsigned d = in.code(5);
        if (d >= 30) return false;
        const int extra = d < 4 ? 0 : static_cast<int>(d / 2 - 1);
        const unsigned base = d < 4 ? d + 1 : ((2U + (d & 1U)) << static_cast<unsigned>(extra)) + 1;
        const std::size_t distance = base + in.bits(extra);
        if (distance > out.size()) return false;
        for (unsigned k = 0; k < length; ++k) out.push_back(out[out.size() - distance]);
    }
}

// Inflates a zlib stream of stored and fixed-Huffman blocks; sets ok to false on anything
// else, on a damaged stream or a wrong Adler-32.
Bytes inflate(const Bytes& z, bool& ok) {
    Bytes out;
    ok = z.size() >= 6 && (z[0] & 0x0FU) == 8 && ((z[0] << 8U) | z[1]) % 31 == 0;
    BitReader in{z, 16};
    for (bool last = false; ok && !last;) {
        last = in.bits(1) != 0;
        const unsigned type = in.bits(2);
        if (type == 1) {
            ok = inflate_fixed_block(in, out);
        } else if (type == 0) {
            in.bit = (in.bit + 7) / 8 * 8;
            const unsigned length = in.bits(16), complement = in.bits(16);
            ok = (length ^ 0xFFFFU) == complement;
            for (unsigned k = 0; ok && k < length; ++k) out.push_back(static_cast<std::uint8_t>(in.bits(8)));
        } else {
            ok = false;
        }
        ok = ok && !in.overrun;
    }
    const std::size_t at = (in.bit + 7) / 8;
    ok = ok && at + 4 == z.size() && big_endian_at(z, at) == grade::adler32(out.data(), out.size());
    return out;
}

// Decodes an 8-bit RGB PNG of filter-0 rows; returns false when anything is off.
bool decode(const Bytes& png, rt::Image& image) {
    const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (png.size() < 8 || std::memcmp(png.data(), signature, 8) != 0) return false;
    Bytes idat;
    bool ended = false;
    for (std::size_t at = 8; at < png.size() && !ended;) {
        const std::uint32_t length = big_endian_at(png, at);
        if (at + 12 + length > png.size()) return false;
        const std::string type(png.begin() + static_cast<std::ptrdiff_t>(at + 4),
                               png.begin() + static_cast<std::ptrdiff_t>(at + 8));
        if (grade::crc32(png.data() + at + 4, length + 4) != big_endian_at(png, at + 8 + length))
            return false;
        const std::uint8_t* data = png.data() + at + 8;
        if (type == "IHDR") {
            image.width = static_cast<int>(big_endian_at(png, at + 8));
            image.height = static_cast<int>(big_endian_at(png, at + 12));
            if (length != 13 || data[8] != 8 || data[9] != 2 || data[10] || data[11] || data[12])
                return false;
        } else if (type == "IDAT") {
            idat.insert(idat.end(), data, data + length);
        } else if (type == "IEND") {
            ended = at + 12 == png.size();
            if (!ended) return false;
        }
        at += 12 + length;
    }
    bool ok = false;
    const Bytes raw = inflate(idat, ok);
    const std::size_t row = 1 + 3 * static_cast<std::size_t>(image.width);
    if (!ok || !ended || raw.size() != row * static_cast<std::size_t>(image.height)) return false;
    image.rgb.clear();
    for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y) {
        if (raw[y * row] != 0) return false;
        image.rgb.insert(image.rgb.end(), raw.begin() + static_cast<std::ptrdiff_t>(y * row + 1),
                         raw.begin() + static_cast<std::ptrdiff_t>((y + 1) * row));
    }
    return true;
}

rt::Image pattern(int width, int height) {
    rt::Image image;
    image.width = width;
    image.height = height;
    for (int i = 0; i < 3 * width * height; ++i)
        image.rgb.push_back(static_cast<std::uint8_t>(i * 7 + i / 13));
    return image;
}

}  // namespace

TEST(checksums_match_the_published_check_values) {
    const std::string text = "123456789";
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
    CHECK(grade::crc32(bytes, text.size()) == 0xCBF43926U);
    CHECK(grade::adler32(bytes, text.size()) == 0x091E01DEU);
    CHECK(grade::adler32(nullptr, 0) == 1U);
}

TEST(images_decode_back_to_the_same_pixels) {
    // 1x1; a few rows; and one over 65535 bytes of image data, so several stored blocks.
    for (const auto& [width, height] : {std::pair{1, 1}, std::pair{7, 3}, std::pair{211, 109}}) {
        const rt::Image image = pattern(width, height);
        rt::Image decoded;
        CHECK(decode(grade::encode_png(image), decoded));
        CHECK(decoded.width == width && decoded.height == height);
        CHECK(decoded.rgb == image.rgb);
    }
}

TEST(flat_and_smooth_images_compress_and_still_decode) {
    // A 600x600 background with a gradient band: matches to the left and above.
    rt::Image image;
    image.width = image.height = 600;
    image.rgb.assign(std::size_t{600} * 600 * 3, 255);
    for (std::size_t i = std::size_t{3} * 600 * 250; i < std::size_t{3} * 600 * 350; ++i)
        image.rgb[i] = static_cast<std::uint8_t>(i / 3 % 600 / 3);
    const Bytes png = grade::encode_png(image);
    CHECK(png.size() < image.rgb.size() / 20);
    rt::Image decoded;
    CHECK(decode(png, decoded));
    CHECK(decoded.rgb == image.rgb);
}

TEST(a_damaged_file_is_refused_by_the_reader) {
    // The reader must be able to fail, or the round trip above would prove nothing.
    Bytes png = grade::encode_png(pattern(5, 4));
    rt::Image decoded;
    png[png.size() / 2] ^= 0x40U;
    CHECK(!decode(png, decoded));
}
