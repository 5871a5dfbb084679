// The numbers of a scene file (SPEC section 2): decimal only, finite in double.
#include "raytracer/scene_numbers.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "raytracer/parser.h"

namespace rt {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Decimal numbers only: [+-] digits [. digits] [(e|E) [+-] digits], with at least one
// digit before or after the point. strtod alone would also take hex, "inf" and "nan".
bool is_decimal_number(std::string_view s) {
    std::size_t i = 0;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t digits = 0;
    while (i < s.size() && is_digit(s[i])) ++i, ++digits;
    if (i < s.size() && s[i] == '.') {
        ++i;
        while (i < s.size() && is_digit(s[i])) ++i, ++digits;
    }
    if (digits == 0) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
        std::size_t exponent_digits = 0;
        while (i < s.size() && is_digit(s[i])) ++i, ++exponent_digits;
        if (exponent_digits == 0) return false;
    }
    return i == s.size();
}

}  // namespace

std::optional<double> out_of_range_decimal(std::string_view token) {
    // strtod decides, as it always did (1e999 overflows and is refused; 1e-999 is 0 and
    // 4e-320 a denormal, both taken). The program never calls setlocale, so strtod
    // reads '.' as the decimal point.
    if (!is_decimal_number(token)) return std::nullopt;
    const std::string text(token);
    const double value = std::strtod(text.c_str(), nullptr);
    if (!std::isfinite(value)) return std::nullopt;
    return value;
}

std::optional<long long> to_integer(std::string_view token) {
    std::size_t i = (!token.empty() && token[0] == '+') ? 1 : 0;
    if (i == token.size()) return std::nullopt;
    long long value = 0;
    for (; i < token.size(); ++i) {
        if (!is_digit(token[i])) return std::nullopt;
        // Saturate rather than overflow: anything this big is refused as too large anyway.
        value = std::min(value * 10 + (token[i] - '0'), kMaxImagePixels + 1);
    }
    return value;
}

}  // namespace rt
