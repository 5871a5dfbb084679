// The two kinds of number a scene file holds, read from one token each.
#pragma once

#include <charconv>
#include <optional>
#include <string_view>
#include <system_error>

namespace rt {

// to_double() of a token that from_chars() found out of range.
std::optional<double> out_of_range_decimal(std::string_view token);

// A decimal number ([+-] digits [. digits] [(e|E) [+-] digits]), finite in double and
// rounded as strtod rounds it; nullopt for anything else (hex, "inf", "nan", 1e999).
// from_chars reads exactly the decimal form (sign, digits, point, exponent) but for a
// leading '+', which it refuses, and "inf" and "nan", which it takes; it rounds
// correctly, as strtod does, and needs no copy nor locale. So the token is first checked
// to start as a number does. Inline: the parser's hottest call on large scenes.
inline std::optional<double> to_double(std::string_view token) {
    std::string_view body = token;
    const bool negative = !body.empty() && body[0] == '-';
    if (!body.empty() && (body[0] == '+' || body[0] == '-')) body.remove_prefix(1);
    if (body.empty() || !((body[0] >= '0' && body[0] <= '9') || body[0] == '.')) return std::nullopt;
    double value = 0;
    const auto [end, error] = std::from_chars(body.data(), body.data() + body.size(), value);
    if (error == std::errc() && end == body.data() + body.size()) return negative ? -value : value;
    if (error == std::errc::result_out_of_range) return out_of_range_decimal(token);
    return std::nullopt;
}

// A whole number ([+] digits), saturated past kMaxImagePixels; nullopt for anything else.
std::optional<long long> to_integer(std::string_view token);

}  // namespace rt
