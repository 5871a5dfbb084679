#include "deflate.h"

#include <algorithm>

namespace grade {
namespace {

// RFC 1951 section 3.2.5: the base and extra bits of the length codes 257..285 and of
// the distance codes 0..29.
constexpr std::uint16_t kLengthBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                           31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::uint8_t kLengthExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                           2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::uint16_t kDistanceBase[30] = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                             33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                             1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::uint8_t kDistanceExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                             6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
constexpr std::size_t kMaxMatch = 258, kMinMatch = 3;

// Bits go out least significant first; Huffman codes are defined most significant bit
// first, so they are reversed on the way in.
struct BitWriter {
    std::vector<std::uint8_t>& out;
    std::uint32_t pending = 0;
    int count = 0;
    void bits(std::uint32_t value, int n) {
        pending |= value << static_cast<unsigned>(count);
        count += n;
        for (; count >= 8; count -= 8, pending >>= 8U)
            out.push_back(static_cast<std::uint8_t>(pending & 0xFFU));
    }
    void code(std::uint32_t value, int n) {
        std::uint32_t reversed = 0;
        for (int i = 0; i < n; ++i) reversed |= ((value >> static_cast<unsigned>(i)) & 1U) << (n - 1 - i);
        bits(reversed, n);
    }
    void flush() {
        if (count > 0) out.push_back(static_cast<std::uint8_t>(pending & 0xFFU));
        pending = 0;
        count = 0;
    }
};

// The fixed literal/length code of RFC 1951 section 3.2.6.
void put_symbol(BitWriter& w, unsigned symbol) {
    if (symbol < 144)
        w.code(0x30 + symbol, 8);
    else if (symbol < 256)
        w.code(0x190 + symbol - 144, 9);
    else if (symbol < 280)
        w.code(symbol - 256, 7);
    else
        w.code(0xC0 + symbol - 280, 8);
}

void put_match(BitWriter& w, std::size_t length, std::size_t distance) {
    unsigned l = 28;
    while (kLengthBase[l] > length) --l;
    put_symbol(w, 257 + l);
    w.bits(static_cast<std::uint32_t>(length - kLengthBase[l]), kLengthExtra[l]);
    unsigned d = 29;
    while (kDistanceBase[d] > distance) --d;
    w.code(d, 5);
    w.bits(static_cast<std::uint32_t>(distance - kDistanceBase[d]), kDistanceExtra[d]);
}

std::size_t match_length(const std::vector<std::uint8_t>& data, std::size_t at, std::size_t distance) {
    if (distance == 0 || distance > at) return 0;
    const std::size_t limit = std::min(kMaxMatch, data.size() - at);
    std::size_t length = 0;
    while (length < limit && data[at + length] == data[at + length - distance]) ++length;
    return length;
}

}  // namespace

std::vector<std::uint8_t> deflate_fixed(const std::vector<std::uint8_t>& data,
                                        const std::vector<std::size_t>& distances) {
    std::vector<std::uint8_t> out;
    BitWriter w{out};
    w.bits(1, 1);  // BFINAL: the only block
    w.bits(1, 2);  // BTYPE 01: fixed Huffman codes
    for (std::size_t at = 0; at < data.size();) {
        std::size_t best_length = 0, best_distance = 0;
        for (const std::size_t distance : distances) {
            const std::size_t length = match_length(data, at, distance);
            if (length > best_length) {
                best_length = length;
                best_distance = distance;
            }
        }
        if (best_length >= kMinMatch) {
            put_match(w, best_length, best_distance);
            at += best_length;
        } else {
            put_symbol(w, data[at]);
            ++at;
        }
    }
    put_symbol(w, 256);  // end of block
    w.flush();
    return out;
}

}  // namespace grade
