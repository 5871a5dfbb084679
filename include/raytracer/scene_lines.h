// The scene file's lines and their tokens (SPEC section 2): a line ends at LF, CR LF or
// a lone CR; its tokens are separated by spaces and tabs (and \v, \f). The parser
// (parser.cpp) reads the text one line at a time with these.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "raytracer/bit_scan.h"

namespace rt {

namespace detail {
// What each byte is to split_line(): part of a token, a field separator, the end of a
// line (CR, LF) or NUL, which never occurs in a text file. One table look-up a byte.
enum ByteKind : unsigned char { kToken, kSeparator, kLineEnd, kNul };
struct ByteKinds {
    unsigned char of[256] = {};
    constexpr ByteKinds() {
        set(" \t\v\f", kSeparator), set("\n\r", kLineEnd);
        of[0] = kNul;
    }
    constexpr void set(const char* bytes, ByteKind kind) {
        for (; *bytes != 0; ++bytes) of[static_cast<unsigned char>(*bytes)] = kind;
    }
};
inline constexpr ByteKinds kByteKinds;
inline unsigned char kind_of(char c) { return kByteKinds.of[static_cast<unsigned char>(c)]; }

// From i, to the first byte below 0x21 (or the end): whole words of eight bytes at a
// time. Every byte that can end a token (a separator, a line end, NUL) is below 0x21,
// and a word holds a byte below 0x21 exactly when (w - 0x21...21) & ~w & 0x80...80 is
// not zero (S. E. Anderson, "Bit Twiddling Hacks": "determine if a word has a byte less
// than n", n <= 128); its lowest set bit marks the first such byte of the word read
// little-endian (a borrow only marks bytes above a true one). The control bytes
// 0x01-0x1F that tokens may hold stop the words too; split_line()'s look-up a byte
// goes on past them. A number's token then costs a few words rather than a look-up a
// byte.
inline std::size_t past_token_words(std::string_view text, std::size_t i) {
    constexpr std::uint64_t kOnes = 0x0101010101010101U, kHighs = 0x8080808080808080U;
    const std::uint64_t one = 1;
    unsigned char first_byte = 0;
    std::memcpy(&first_byte, &one, 1);
    const bool little_endian = first_byte == 1;  // a constant to the compiler
    for (std::uint64_t w; i + 8 <= text.size(); i += 8) {
        std::memcpy(&w, text.data() + i, 8);
        const std::uint64_t below = (w - 0x21 * kOnes) & ~w & kHighs;
        if (below != 0) return little_endian ? i + static_cast<std::size_t>(lowest_bit(below) / 8) : i;
    }
    return i;
}
}  // namespace detail

// A line's tokens: the first kKept of them (a SPHERE line's keyword and 15 fields), and
// how many there are in all, so that a line of millions of tokens is counted for its
// message, not stored.
struct LineTokens {
    static constexpr std::size_t kKept = 16;
    std::string_view kept[kKept];
    std::size_t count = 0;

    bool empty() const { return count == 0; }
    std::string_view operator[](std::size_t i) const { return kept[i]; }  // i < min(count, kKept)
};

// Splits the first line of text into tokens and returns where it ends: at its first CR
// or LF, or at the end; npos if it holds a NUL byte.
inline std::size_t split_line(std::string_view text, LineTokens& tokens) {
    tokens.count = 0;
    std::size_t i = 0;
    const std::size_t n = text.size();
    for (;;) {
        while (i < n && detail::kind_of(text[i]) == detail::kSeparator) ++i;
        if (i == n || detail::kind_of(text[i]) == detail::kLineEnd) return i;
        if (detail::kind_of(text[i]) == detail::kNul) return std::string_view::npos;
        const std::size_t start = i;
        i = detail::past_token_words(text, i);
        while (i < n && detail::kind_of(text[i]) == detail::kToken) ++i;
        if (tokens.count < LineTokens::kKept) tokens.kept[tokens.count] = text.substr(start, i - start);
        ++tokens.count;
    }
}

// Where the next line starts after a line that ends at end: past LF, CR LF or a lone CR
// (old Mac files), each of which ends one line.
inline std::size_t next_line(std::string_view text, std::size_t end) {
    std::size_t next = end == text.size() ? end : end + 1;
    if (end < text.size() && text[end] == '\r' && next < text.size() && text[next] == '\n') ++next;
    return next;
}

}  // namespace rt
