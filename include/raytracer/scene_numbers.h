// The two kinds of number a scene file holds, read from one token each.
#pragma once

#include <optional>
#include <string_view>

namespace rt {

// A decimal number ([+-] digits [. digits] [(e|E) [+-] digits]), finite in double and
// rounded as strtod rounds it; nullopt for anything else (hex, "inf", "nan", 1e999).
std::optional<double> to_double(std::string_view token);

// A whole number ([+] digits), saturated past kMaxImagePixels; nullopt for anything else.
std::optional<long long> to_integer(std::string_view token);

}  // namespace rt
