#include "raytracer/shown.h"

#include <algorithm>

namespace rt {

namespace {

bool printable(unsigned char c) { return c >= 0x20 && c < 0x7f; }

void append_escaped(std::string& out, std::string_view text, std::size_t most) {
    static const char* const hex = "0123456789abcdef";
    text = text.substr(0, most);
    const bool escapes = std::any_of(text.begin(), text.end(),
                                     [](char c) { return !printable(static_cast<unsigned char>(c)); });
    for (const char byte : text) {
        const auto c = static_cast<unsigned char>(byte);
        if (c == '\\' && escapes) {
            out += "\\\\";
        } else if (printable(c)) {
            out += byte;
        } else {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
}

}  // namespace

std::string escaped(std::string_view text, std::size_t most) {
    std::string out;
    append_escaped(out, text, most);
    if (text.size() > most) out += "... (" + std::to_string(text.size()) + " bytes)";
    return out;
}

std::string shown(std::string_view text, std::size_t most) {
    std::string out = "'";
    append_escaped(out, text, most);
    if (text.size() > most)
        out += "...' (" + std::to_string(text.size()) + " bytes)";
    else
        out += "'";
    return out;
}

std::string plural(long long count, const char* one, const char* many) {
    return std::to_string(count) + " " + (count == 1 ? one : many);
}

}  // namespace rt
