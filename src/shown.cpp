#include "raytracer/shown.h"

namespace rt {

namespace {

bool printable(unsigned char c) { return c >= 0x20 && c < 0x7f; }

void append_hex(std::string& out, unsigned char c) {
    static const char* const hex = "0123456789abcdef";
    out += "\\x";
    out += hex[c >> 4];
    out += hex[c & 15];
}

void append_escaped(std::string& out, std::string_view text, std::size_t most) {
    text = text.substr(0, most);
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        const bool reads_as_escape = c == '\\' && i + 1 < text.size() && text[i + 1] == 'x';
        if (printable(c) && !reads_as_escape)
            out += text[i];
        else
            append_hex(out, c);
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

std::string controls_escaped(std::string_view text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        // C1 controls (U+0080 to U+009F) as UTF-8 writes them: C2 80 to C2 9F.
        const bool c1 =
            c == 0xC2 && i + 1 < text.size() && (static_cast<unsigned char>(text[i + 1]) & 0xE0U) == 0x80U;
        if (c1) {
            append_hex(out, c), append_hex(out, static_cast<unsigned char>(text[++i]));
        } else if (c < 0x20 || c == 0x7F) {
            append_hex(out, c);
        } else {
            out += text[i];
        }
    }
    return out;
}

std::string plural(long long count, const char* one, const char* many) {
    return std::to_string(count) + " " + (count == 1 ? one : many);
}

}  // namespace rt
