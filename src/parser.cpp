// Scene-file parsing. One statement per line: a keyword and a fixed number of fields,
// all separated by spaces, tabs or CR (SPEC section 2). Reading line by line, rather
// than as one token stream, lets a short SPHERE line be reported on its own line.
#include "raytracer/parser.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include "raytracer/scene_error.h"
#include "raytracer/shown.h"

namespace rt {
namespace {

// Field separators within a line (CR and LF end lines).
bool is_separator(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
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

std::optional<double> to_double(std::string_view token) {
    // from_chars reads exactly the decimal form (sign, digits, point, exponent) but for
    // a leading '+', which it refuses, and "inf" and "nan", which it takes; it rounds
    // correctly, as strtod does, and needs no copy nor locale (the parser's hottest call
    // on large scenes). So the token is first checked to start as a number does.
    std::string_view body = token;
    const bool negative = !body.empty() && body[0] == '-';
    if (!body.empty() && (body[0] == '+' || body[0] == '-')) body.remove_prefix(1);
    if (body.empty() || !(is_digit(body[0]) || body[0] == '.')) return std::nullopt;
    double value = 0;
    const auto [end, error] = std::from_chars(body.data(), body.data() + body.size(), value);
    if (error == std::errc() && end == body.data() + body.size()) return negative ? -value : value;
    // Out of range: strtod decides, as it always did (1e999 overflows and is refused;
    // 1e-999 is 0 and 4e-320 a denormal, both taken). The program never calls
    // setlocale, so strtod reads '.' as the decimal point.
    if (error != std::errc::result_out_of_range || !is_decimal_number(token)) return std::nullopt;
    const std::string text(token);
    value = std::strtod(text.c_str(), nullptr);
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

enum class Field { Name, Number, Count };

struct Statement {
    const char* keyword;
    bool required_once;  // false: SPHERE and LIGHT, any number of times
    std::vector<const char*> field_names;
    std::vector<Field> field_kinds;
};

const std::vector<Statement>& statements() {
    using F = Field;
    static const std::vector<Statement> table = {
        {"NEAR", true, {"n"}, {F::Number}},
        {"LEFT", true, {"l"}, {F::Number}},
        {"RIGHT", true, {"r"}, {F::Number}},
        {"BOTTOM", true, {"b"}, {F::Number}},
        {"TOP", true, {"t"}, {F::Number}},
        {"RES", true, {"x", "y"}, {F::Count, F::Count}},
        {"SPHERE",
         false,
         {"name", "pos x", "pos y", "pos z", "scl x", "scl y", "scl z", "r", "g", "b", "Ka", "Kd", "Ks", "Kr",
          "n"},
         {F::Name, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number,
          F::Number, F::Number, F::Number, F::Number, F::Number, F::Number}},
        {"LIGHT",
         false,
         {"name", "pos x", "pos y", "pos z", "Ir", "Ig", "Ib"},
         {F::Name, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number}},
        {"BACK", true, {"r", "g", "b"}, {F::Number, F::Number, F::Number}},
        {"AMBIENT", true, {"Ir", "Ig", "Ib"}, {F::Number, F::Number, F::Number}},
        {"OUTPUT", true, {"name"}, {F::Name}},
    };
    return table;
}

std::string usage_of(const Statement& s) {
    std::string text = s.keyword;
    for (const char* name : s.field_names) text += std::string(" <") + name + ">";
    return text;
}

std::string keyword_list() {
    std::string text;
    for (const Statement& s : statements()) text += (text.empty() ? "" : ", ") + std::string(s.keyword);
    return text;
}

// Splits the first line of text into tokens (reused from line to line: no allocation
// per line) and returns where it ends: at its first CR or LF, or at the end. One pass
// over the bytes; find_first_of() would look each byte up in the set with a call to
// memchr, a quarter of the time spent reading a large scene.
std::size_t split_line(std::string_view text, std::vector<std::string_view>& tokens) {
    tokens.clear();
    std::size_t i = 0;
    const std::size_t n = text.size();
    for (;;) {
        while (i < n && is_separator(text[i])) ++i;
        if (i == n || text[i] == '\n' || text[i] == '\r') return i;
        const std::size_t start = i;
        while (i < n && !is_separator(text[i]) && text[i] != '\n' && text[i] != '\r') ++i;
        tokens.push_back(text.substr(start, i - start));
    }
}

// The fields of one statement, converted and checked for form (not yet for meaning).
struct Fields {
    std::vector<std::string_view> names;
    std::vector<double> numbers;
    std::vector<long long> counts;
    std::vector<std::string_view> raw;  // every field as written, for messages
};

class SceneParser {
public:
    explicit SceneParser(const std::string& file) : file_(file) {}

    Scene parse(std::string_view text) {
        // At most one ellipsoid per "SPHERE" in the text: reserved, so that the list
        // is not copied as it grows (nor its peak twice its size).
        std::size_t spheres = 0;
        for (std::size_t at = text.find("SPHERE"); at != std::string_view::npos;
             at = text.find("SPHERE", at + 6))
            ++spheres;
        scene_.spheres.reserve(spheres);
        // A UTF-8 byte-order mark, as some Windows editors write, is not part of the scene.
        if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
        int line_number = 0;
        while (!text.empty()) {
            ++line_number;
            // A line ends at LF, CR LF, or a lone CR (old Mac files): each counts as one line.
            const std::size_t end = split_line(text, tokens_);
            // A NUL byte never occurs in a text file; say so rather than "unknown keyword".
            // Checked line by line, so that the first mistake in the file is the one reported.
            if (text.substr(0, end).find('\0') != std::string_view::npos)
                fail(line_number, "a NUL byte (a binary file?), expected a text scene file");
            statement(tokens_, line_number);
            std::size_t next = end == text.size() ? end : end + 1;
            if (end < text.size() && text[end] == '\r' && next < text.size() && text[next] == '\n') ++next;
            text.remove_prefix(next);
        }
        check_complete();
        return scene_;
    }

private:
    [[noreturn]] void fail(int line, const std::string& what) const { throw SceneError(file_, line, what); }

    void statement(const std::vector<std::string_view>& tokens, int line) {
        if (tokens.empty()) return;  // blank lines are allowed anywhere
        const Statement* found = nullptr;
        for (const Statement& s : statements())
            if (tokens[0] == s.keyword) found = &s;
        if (found == nullptr)
            fail(line, "unknown keyword " + shown(tokens[0]) + ", expected one of " + keyword_list());

        const std::size_t given = tokens.size() - 1;
        const std::size_t wanted = found->field_names.size();
        if (given != wanted) {
            fail(line, std::string(found->keyword) + " has " + std::to_string(given) + " field" +
                           (given == 1 ? "" : "s") + ", expected " + std::to_string(wanted) + ": " +
                           usage_of(*found));
        }

        const std::size_t index = static_cast<std::size_t>(found - statements().data());
        if (found->required_once) {
            if (first_line_[index] != 0) {
                fail(line, std::string("a second ") + found->keyword + " (the first is on line " +
                               std::to_string(first_line_[index]) + "), expected exactly one");
            }
            first_line_[index] = line;
        }

        Fields& fields = fields_;  // reused: no allocation per line
        fields.names.clear(), fields.numbers.clear(), fields.counts.clear(), fields.raw.clear();
        for (std::size_t i = 0; i < wanted; ++i) {
            const std::string_view token = tokens[i + 1];
            fields.raw.push_back(token);
            auto what = [&] {  // only for a message: most lines have none
                return std::string(found->keyword) + " <" + found->field_names[i] + "> is " + shown(token);
            };
            switch (found->field_kinds[i]) {
                case Field::Name:
                    fields.names.push_back(token);
                    break;
                case Field::Number:
                    if (auto value = to_double(token))
                        fields.numbers.push_back(*value);
                    else
                        fail(line, what() + ", expected a finite decimal number");
                    break;
                case Field::Count:
                    if (auto value = to_integer(token); value && *value > 0)
                        fields.counts.push_back(*value);
                    else
                        fail(line, what() + ", expected a positive whole number");
                    break;
            }
        }
        apply(found->keyword, fields, line);
    }

    void apply(std::string_view keyword, const Fields& f, int line) {
        const std::vector<double>& v = f.numbers;
        if (keyword == "NEAR") {
            if (!(v[0] > 0)) fail(line, "NEAR is " + format(v[0]) + ", expected a distance greater than 0");
            scene_.near_plane = v[0];
        } else if (keyword == "LEFT") {
            scene_.left = v[0];
        } else if (keyword == "RIGHT") {
            scene_.right = v[0];
        } else if (keyword == "BOTTOM") {
            scene_.bottom = v[0];
        } else if (keyword == "TOP") {
            scene_.top = v[0];
        } else if (keyword == "RES") {
            const long long columns = f.counts[0], rows = f.counts[1];
            if (columns > kMaxImageSide || rows > kMaxImageSide || columns * rows > kMaxImagePixels) {
                fail(line, "RES " + std::to_string(columns) + " " + std::to_string(rows) +
                               " is too large, expected at most " + std::to_string(kMaxImageSide) +
                               " a side and " + std::to_string(kMaxImagePixels) + " pixels");
            }
            scene_.columns = static_cast<int>(columns);
            scene_.rows = static_cast<int>(rows);
        } else if (keyword == "SPHERE") {
            SphereSpec s;
            s.name = std::string(f.names[0]);
            s.centre = {v[0], v[1], v[2]};
            s.scale = {v[3], v[4], v[5]};
            s.colour = {v[6], v[7], v[8]};
            s.ka = v[9];
            s.kd = v[10];
            s.ks = v[11];
            s.kr = v[12];
            s.shininess = v[13];
            s.line = line;
            for (std::size_t axis = 0; axis < 3; ++axis) {
                if (v[3 + axis] == 0) {
                    fail(line, "SPHERE " + shown(s.name) + " <scl " + "xyz"[axis] + "> is " +
                                   shown(f.raw[4 + axis]) + ", expected a non-zero scale");
                }
            }
            scene_.spheres.push_back(std::move(s));
        } else if (keyword == "LIGHT") {
            scene_.lights.push_back({std::string(f.names[0]), {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, line});
        } else if (keyword == "BACK") {
            scene_.background = {v[0], v[1], v[2]};
        } else if (keyword == "AMBIENT") {
            scene_.ambient = {v[0], v[1], v[2]};
        } else if (keyword == "OUTPUT") {
            scene_.output = std::string(f.names[0]);
            scene_.output_line = line;
        }
    }

    static std::string format(double value) {
        std::ostringstream out;
        out << value;
        return out.str();
    }

    int line_of(std::string_view keyword) const {
        for (std::size_t i = 0; i < statements().size(); ++i)
            if (keyword == statements()[i].keyword) return first_line_[i];
        return 0;
    }

    void check_complete() const {
        for (std::size_t i = 0; i < statements().size(); ++i) {
            if (statements()[i].required_once && first_line_[i] == 0) {
                fail(0, std::string("no ") + statements()[i].keyword +
                            " line, expected exactly one: " + usage_of(statements()[i]));
            }
        }
        // Each pair is reported on the line of whichever of the two came later.
        if (!(scene_.left < scene_.right)) {
            fail(std::max(line_of("LEFT"), line_of("RIGHT")), "LEFT " + format(scene_.left) + " and RIGHT " +
                                                                  format(scene_.right) +
                                                                  ", expected LEFT < RIGHT");
        }
        if (!(scene_.bottom < scene_.top)) {
            fail(std::max(line_of("BOTTOM"), line_of("TOP")), "BOTTOM " + format(scene_.bottom) +
                                                                  " and TOP " + format(scene_.top) +
                                                                  ", expected BOTTOM < TOP");
        }
    }

    std::string file_;
    Scene scene_;
    std::vector<std::string_view> tokens_;                                 // of the current line
    Fields fields_;                                                        // of the current line
    std::vector<int> first_line_ = std::vector<int>(statements().size());  // per kind: its first line
};

}  // namespace

Scene parse_scene(std::string_view text, const std::string& file_name) {
    return SceneParser(file_name).parse(text);
}

Scene load_scene(const std::string& path) {
    // C stdio rather than an ifstream, and the file system asked only when the file
    // cannot be read: an ifstream's first use sets up locale facets, and the two status
    // queries cost system calls; together 0.1 ms of a 2 ms run (docs/speed.md).
    auto cannot_read = [&path](bool opened, int error) {
        std::error_code ec;
        // Where a folder opens (Linux), reading it fails.
        if (std::filesystem::is_directory(path, ec))
            return SceneError(path, 0, "is a directory, expected a scene file");
        if (!opened && error == ENOENT) return SceneError(path, 0, "does not exist, expected a scene file");
        if (!opened && error == EACCES)
            return SceneError(
                path, 0, "cannot be opened for reading: permission denied, expected a readable scene file");
        if (!opened && !std::filesystem::exists(path, ec))
            return SceneError(path, 0, "does not exist, expected a scene file");
        const std::string cause = error != 0 ? std::string(": ") + std::strerror(error) : std::string();
        return opened
                   ? SceneError(path, 0, "could not be read" + cause + ", expected a readable scene file")
                   : SceneError(path, 0,
                                "cannot be opened for reading" + cause + ", expected a readable scene file");
    };
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!in) throw cannot_read(false, errno);
    std::string text;
    // Reserved at the file's size where the system tells it (one allocation, not a
    // doubling string's: a 26 MB scene then peaks at 26 MB, not 48).
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size <= kMaxSceneFileBytes) text.reserve(static_cast<std::size_t>(size));
    char buffer[1 << 14];
    for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, in.get())) > 0;) {
        text.append(buffer, got);
        if (text.size() > kMaxSceneFileBytes) {
            throw SceneError(
                path, 0,
                "is larger than " + std::to_string(kMaxSceneFileBytes >> 20) + " MiB, expected a scene file");
        }
    }
    if (std::ferror(in.get()) != 0) throw cannot_read(true, errno);
    if (text.find_first_not_of(" \t\r\n\v\f") == std::string::npos)
        throw SceneError(path, 0, "is empty, expected a scene file");
    // Windows editors may save UTF-16, whose ASCII letters come with NUL bytes between.
    if (text.rfind("\xFF\xFE", 0) == 0 || text.rfind("\xFE\xFF", 0) == 0)
        throw SceneError(path, 0, "is UTF-16 text, expected ASCII or UTF-8 text");
    return parse_scene(text, path);
}

}  // namespace rt
