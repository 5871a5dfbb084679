// The statements of a scene file (SPEC section 2) and their checks: the keyword table,
// the fields of one line converted and checked for form, and SceneBuilder, which
// applies a line's statement to a Scene and checks the scene once it is complete. The
// reading of the text, line by line and in pieces, is parser.cpp's.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "raytracer/parser.h"
#include "raytracer/scene.h"
#include "raytracer/scene_lines.h"
#include "raytracer/scene_numbers.h"
#include "raytracer/shown.h"

namespace rt::statements_of_scenes {

enum class Field { Name, Number, Count };
// Left, Right, Bottom and Top in this order: SceneBuilder::window_side() numbers them so.
enum class Keyword { Near, Left, Right, Bottom, Top, Res, Sphere, Light, Back, Ambient, Output };

struct Statement {
    Keyword kind;
    std::string_view keyword;
    bool required_once;  // false: SPHERE and LIGHT, any number of times
    std::vector<const char*> field_names;
    std::vector<Field> field_kinds;
};

inline const std::vector<Statement>& statements() {
    using F = Field;
    using K = Keyword;
    static const std::vector<Statement> table = {
        {K::Near, "NEAR", true, {"n"}, {F::Number}},
        {K::Left, "LEFT", true, {"l"}, {F::Number}},
        {K::Right, "RIGHT", true, {"r"}, {F::Number}},
        {K::Bottom, "BOTTOM", true, {"b"}, {F::Number}},
        {K::Top, "TOP", true, {"t"}, {F::Number}},
        {K::Res, "RES", true, {"x", "y"}, {F::Count, F::Count}},
        {K::Sphere,
         "SPHERE",
         false,
         {"name", "pos x", "pos y", "pos z", "scl x", "scl y", "scl z", "r", "g", "b", "Ka", "Kd", "Ks", "Kr",
          "n"},
         {F::Name, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number,
          F::Number, F::Number, F::Number, F::Number, F::Number, F::Number}},
        {K::Light,
         "LIGHT",
         false,
         {"name", "pos x", "pos y", "pos z", "Ir", "Ig", "Ib"},
         {F::Name, F::Number, F::Number, F::Number, F::Number, F::Number, F::Number}},
        {K::Back, "BACK", true, {"r", "g", "b"}, {F::Number, F::Number, F::Number}},
        {K::Ambient, "AMBIENT", true, {"Ir", "Ig", "Ib"}, {F::Number, F::Number, F::Number}},
        {K::Output, "OUTPUT", true, {"name"}, {F::Name}},
    };
    return table;
}

inline std::string usage_of(const Statement& s) {
    std::string text(s.keyword);
    for (const char* name : s.field_names) text += std::string(" <") + name + ">";
    return text;
}

inline std::string keyword_list() {
    std::string text;
    for (const Statement& s : statements()) text += (text.empty() ? "" : ", ") + std::string(s.keyword);
    return text;
}

// A mistake: its line (0: the file as a whole) and what is wrong. A piece of the text
// counts its lines from its own first; the merge turns it into a SceneError.
struct Failure {
    int line;
    std::string what;
};
[[noreturn]] inline void fail(int line, std::string what) { throw Failure{line, std::move(what)}; }

inline const Statement& statement_of(std::string_view keyword, int line) {
    for (const Statement& s : statements())
        if (keyword == s.keyword) return s;
    fail(line, "unknown keyword " + shown(keyword) + ", expected one of " + keyword_list());
}

// The fields of one statement, converted and checked for form (not yet for meaning),
// each kind in the order given: no allocation per line.
struct Fields {
    static constexpr std::size_t kMax = 15;  // SPHERE's
    static_assert(kMax + 1 <= LineTokens::kKept, "a statement's keyword and fields are kept whole");
    std::string_view names[kMax], raw[kMax];  // raw: every field as written, for messages
    double numbers[kMax] = {};
    long long counts[kMax] = {};
};

// Applies statements to a scene, checking each, and the scene once it is complete.
class SceneBuilder {
public:
    Scene scene;

    void statement(const Statement& found, const LineTokens& tokens, int line) {
        const std::size_t given = tokens.count - 1;
        const std::size_t wanted = found.field_names.size();
        if (given != wanted) {
            fail(line, std::string(found.keyword) + " has " +
                           plural(static_cast<long long>(given), "field", "fields") + ", expected " +
                           std::to_string(wanted) + ": " + usage_of(found));
        }

        const std::size_t index = static_cast<std::size_t>(&found - statements().data());
        if (found.required_once) {
            if (first_line_[index] != 0) {
                fail(line, "a second " + std::string(found.keyword) + " (the first is on line " +
                               std::to_string(first_line_[index]) + "), expected exactly one");
            }
            first_line_[index] = line;
        }

        Fields& f = fields_;  // reused: its arrays are not set up a line
        std::size_t names = 0, numbers = 0, counts = 0;
        for (std::size_t i = 0; i < wanted; ++i) {
            const std::string_view token = tokens[i + 1];
            f.raw[i] = token;
            auto what = [&] {  // only for a message: most lines have none
                return std::string(found.keyword) + " <" + found.field_names[i] + "> is " + shown(token);
            };
            switch (found.field_kinds[i]) {
                case Field::Name:
                    f.names[names++] = token;
                    break;
                case Field::Number:
                    if (auto value = to_double(token))
                        f.numbers[numbers++] = *value;
                    else
                        fail(line, what() + ", expected a finite decimal number");
                    break;
                case Field::Count:
                    if (auto value = to_integer(token); value && *value > 0)
                        f.counts[counts++] = *value;
                    else
                        fail(line, what() + ", expected a positive whole number");
                    break;
            }
        }
        apply(found.kind, f, line);
    }

    void apply(Keyword kind, const Fields& f, int line) {
        using K = Keyword;
        const double* v = f.numbers;
        if (kind == K::Near) {
            if (!(v[0] > 0))
                fail(line, "NEAR is " + as_written(f.raw[0], v[0]) + ", expected a distance greater than 0");
            scene.near_plane = v[0];
        } else if (kind == K::Left || kind == K::Right || kind == K::Bottom || kind == K::Top) {
            window_side(static_cast<int>(kind) - static_cast<int>(K::Left), v[0], f.raw[0], line);
        } else if (kind == K::Res) {
            const long long columns = f.counts[0], rows = f.counts[1];
            if (columns > kMaxImageSide || rows > kMaxImageSide || columns * rows > kMaxImagePixels) {
                fail(line, "RES " + escaped(f.raw[0], kMaxShownToken) + " " +
                               escaped(f.raw[1], kMaxShownToken) + " is too large, expected at most " +
                               std::to_string(kMaxImageSide) + " a side and " +
                               std::to_string(kMaxImagePixels) + " pixels");
            }
            scene.columns = static_cast<int>(columns);
            scene.rows = static_cast<int>(rows);
        } else if (kind == K::Sphere) {
            for (std::size_t axis = 0; axis < 3; ++axis) {
                if (v[3 + axis] == 0) {
                    fail(line, "SPHERE " + shown(f.names[0]) + " <scl " + "xyz"[axis] + "> is " +
                                   shown(f.raw[4 + axis]) + read_as_zero(f.raw[4 + axis]) +
                                   ", expected a non-zero scale");
                }
            }
            SphereSpec& s = scene.spheres.emplace_back();
            s.centre = {v[0], v[1], v[2]}, s.scale = {v[3], v[4], v[5]}, s.colour = {v[6], v[7], v[8]};
            s.ka = v[9], s.kd = v[10], s.ks = v[11], s.kr = v[12], s.shininess = v[13];
            s.line = line;
        } else if (kind == K::Light) {
            scene.lights.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, line});
        } else if (kind == K::Back) {
            scene.background = {v[0], v[1], v[2]};
        } else if (kind == K::Ambient) {
            scene.ambient = {v[0], v[1], v[2]};
        } else if (kind == K::Output) {
            scene.output = std::string(f.names[0]);
            scene.output_line = line;
        }
    }

    // A number's token as the file writes it (not rounded for the message: LEFT 0.3000001
    // and RIGHT 0.3 are told apart).
    static std::string as_written(std::string_view raw, double value) {
        return escaped(raw, kMaxShownToken) + (value == 0 ? read_as_zero(raw) : std::string());
    }
    // LEFT, RIGHT, BOTTOM or TOP (side 0 to 3): its value, and its pair checked once both
    // are known, on the line of the later of the two, where the mistake shows.
    void window_side(int side, double value, std::string_view raw, int line) {
        static constexpr const char* kNames[4] = {"LEFT", "RIGHT", "BOTTOM", "TOP"};
        double* const values[4] = {&scene.left, &scene.right, &scene.bottom, &scene.top};
        *values[side] = value;
        window_[side] = as_written(raw, value);
        const int low = side & ~1, high = low + 1;
        if (line_of(kNames[low]) == 0 || line_of(kNames[high]) == 0 || *values[low] < *values[high]) return;
        // Rounding keeps the tokens' order, so only a tie in double can look right as written
        // (0.3 and 0.30000000000000001).
        const bool tie = *values[low] == *values[high] && window_[low] != window_[high];
        fail(line, std::string(kNames[low]) + " " + window_[low] + " and " + kNames[high] + " " +
                       window_[high] + (tie ? " (equal in double)" : "") + ", expected " + kNames[low] +
                       " < " + kNames[high]);
    }
    // Why a token that is no zero as written reads as 0: it lies below double's range.
    static std::string read_as_zero(std::string_view raw) {
        const std::string_view digits = raw.substr(0, raw.find_first_of("eE"));
        return digits.find_first_of("123456789") != std::string_view::npos ? " (below double's range: 0)"
                                                                           : std::string();
    }

    int line_of(std::string_view keyword) const {
        for (std::size_t i = 0; i < statements().size(); ++i)
            if (keyword == statements()[i].keyword) return first_line_[i];
        return 0;
    }

    void check_complete() const {
        for (std::size_t i = 0; i < statements().size(); ++i) {
            if (statements()[i].required_once && first_line_[i] == 0) {
                fail(0, "no " + std::string(statements()[i].keyword) +
                            " line, expected exactly one: " + usage_of(statements()[i]));
            }
        }
    }

private:
    Fields fields_;          // of the current line
    std::string window_[4];  // LEFT, RIGHT, BOTTOM and TOP as written, for a message
    std::vector<int> first_line_ = std::vector<int>(statements().size());  // per kind: its first line
};

}  // namespace rt::statements_of_scenes
