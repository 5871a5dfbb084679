// Scene-file parsing. One statement per line: a keyword and a fixed number of fields,
// all separated by spaces, tabs or CR (SPEC section 2). Reading line by line, rather
// than as one token stream, lets a short SPHERE line be reported on its own line.
// A large text is cut into pieces at line starts, parsed at once on the helper threads
// and merged in file order (Piece, merge()): the same scene, and the same first mistake.
#include "raytracer/parser.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "raytracer/helper_pool.h"
#include "raytracer/large_pages.h"
#include "raytracer/scene_error.h"
#include "raytracer/scene_lines.h"
#include "raytracer/scene_numbers.h"
#include "raytracer/shown.h"

namespace rt {
namespace {

enum class Field { Name, Number, Count };
enum class Keyword { Near, Left, Right, Bottom, Top, Res, Sphere, Light, Back, Ambient, Output };

struct Statement {
    Keyword kind;
    std::string_view keyword;
    bool required_once;  // false: SPHERE and LIGHT, any number of times
    std::vector<const char*> field_names;
    std::vector<Field> field_kinds;
};

const std::vector<Statement>& statements() {
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

std::string usage_of(const Statement& s) {
    std::string text(s.keyword);
    for (const char* name : s.field_names) text += std::string(" <") + name + ">";
    return text;
}

std::string keyword_list() {
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
[[noreturn]] void fail(int line, std::string what) { throw Failure{line, std::move(what)}; }

const Statement& statement_of(std::string_view keyword, int line) {
    for (const Statement& s : statements())
        if (keyword == s.keyword) return s;
    fail(line, "unknown keyword " + shown(keyword) + ", expected one of " + keyword_list());
}

// The fields of one statement, converted and checked for form (not yet for meaning),
// each kind in the order given: no allocation per line.
struct Fields {
    static constexpr std::size_t kMax = 15;   // SPHERE's
    std::string_view names[kMax], raw[kMax];  // raw: every field as written, for messages
    double numbers[kMax] = {};
    long long counts[kMax] = {};
};

// Applies statements to a scene, checking each, and the scene once it is complete.
class SceneBuilder {
public:
    Scene scene;

    void statement(const Statement& found, const std::vector<std::string_view>& tokens, int line) {
        const std::size_t given = tokens.size() - 1;
        const std::size_t wanted = found.field_names.size();
        if (given != wanted) {
            fail(line, std::string(found.keyword) + " has " + std::to_string(given) + " field" +
                           (given == 1 ? "" : "s") + ", expected " + std::to_string(wanted) + ": " +
                           usage_of(found));
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
            if (!(v[0] > 0)) fail(line, "NEAR is " + format(v[0]) + ", expected a distance greater than 0");
            scene.near_plane = v[0];
        } else if (kind == K::Left) {
            scene.left = v[0];
        } else if (kind == K::Right) {
            scene.right = v[0];
        } else if (kind == K::Bottom) {
            scene.bottom = v[0];
        } else if (kind == K::Top) {
            scene.top = v[0];
        } else if (kind == K::Res) {
            const long long columns = f.counts[0], rows = f.counts[1];
            if (columns > kMaxImageSide || rows > kMaxImageSide || columns * rows > kMaxImagePixels) {
                fail(line, "RES " + std::to_string(columns) + " " + std::to_string(rows) +
                               " is too large, expected at most " + std::to_string(kMaxImageSide) +
                               " a side and " + std::to_string(kMaxImagePixels) + " pixels");
            }
            scene.columns = static_cast<int>(columns);
            scene.rows = static_cast<int>(rows);
        } else if (kind == K::Sphere) {
            for (std::size_t axis = 0; axis < 3; ++axis) {
                if (v[3 + axis] == 0) {
                    fail(line, "SPHERE " + shown(f.names[0]) + " <scl " + "xyz"[axis] + "> is " +
                                   shown(f.raw[4 + axis]) + ", expected a non-zero scale");
                }
            }
            SphereSpec& s = scene.spheres.emplace_back();
            s.name = f.names[0];
            s.centre = {v[0], v[1], v[2]}, s.scale = {v[3], v[4], v[5]}, s.colour = {v[6], v[7], v[8]};
            s.ka = v[9], s.kd = v[10], s.ks = v[11], s.kr = v[12], s.shininess = v[13];
            s.line = line;
        } else if (kind == K::Light) {
            scene.lights.push_back({std::string(f.names[0]), {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, line});
        } else if (kind == K::Back) {
            scene.background = {v[0], v[1], v[2]};
        } else if (kind == K::Ambient) {
            scene.ambient = {v[0], v[1], v[2]};
        } else if (kind == K::Output) {
            scene.output = std::string(f.names[0]);
            scene.output_line = line;
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
                fail(0, "no " + std::string(statements()[i].keyword) +
                            " line, expected exactly one: " + usage_of(statements()[i]));
            }
        }
        // Each pair is reported on the line of whichever of the two came later.
        if (!(scene.left < scene.right)) {
            fail(std::max(line_of("LEFT"), line_of("RIGHT")), "LEFT " + format(scene.left) + " and RIGHT " +
                                                                  format(scene.right) +
                                                                  ", expected LEFT < RIGHT");
        }
        if (!(scene.bottom < scene.top)) {
            fail(std::max(line_of("BOTTOM"), line_of("TOP")), "BOTTOM " + format(scene.bottom) + " and TOP " +
                                                                  format(scene.top) +
                                                                  ", expected BOTTOM < TOP");
        }
    }

private:
    Fields fields_;                                                        // of the current line
    std::vector<int> first_line_ = std::vector<int>(statements().size());  // per kind: its first line
};

// A piece of the text, from a line's start to the next piece's, parsed on its own: its
// spheres and lights. The statements that must occur once are kept for the merge, which
// alone knows whether an earlier piece had one: so that a piece stops at the same
// first mistake as the whole file would. Nothing else carries from line to line.
struct Piece {
    std::string_view text;
    // Its list of spheres is reserved for one per "SPHERE" in this text: the first
    // piece's for the whole text, as the merge appends the other pieces' to it.
    std::string_view reserve_for;
    SceneBuilder spheres_and_lights;
    std::vector<std::pair<int, std::string_view>> once;  // each line and the text from it on
    int lines = 0;
    std::optional<Failure> failure;  // the piece's first mistake: it stops there
    std::exception_ptr exception;    // anything else (out of memory), rethrown in the merge

    void parse() {
        try {
            // At most one ellipsoid per "SPHERE": reserved, so that the list is not
            // copied as it grows (nor its peak twice its size).
            std::size_t spheres = 0;
            for (std::size_t at = reserve_for.find("SPHERE"); at != std::string_view::npos;
                 at = reserve_for.find("SPHERE", at + 6))
                ++spheres;
            reserve_large(spheres_and_lights.scene.spheres, spheres);
            std::vector<std::string_view> tokens;  // of the current line
            for (std::string_view rest = text; !rest.empty();) {
                ++lines;
                const std::size_t end = split_line(rest, tokens);
                // A NUL byte never occurs in a text file; say so rather than "unknown keyword".
                if (end == std::string_view::npos)
                    fail(lines, "a NUL byte (a binary file?), expected a text scene file");
                if (!tokens.empty()) {  // blank lines are allowed anywhere
                    const Statement& s = statement_of(tokens[0], lines);
                    if (s.required_once)
                        once.emplace_back(lines, rest);
                    else
                        spheres_and_lights.statement(s, tokens, lines);
                }
                rest.remove_prefix(next_line(rest, end));
            }
        } catch (Failure& f) {
            failure = std::move(f);
        } catch (...) {
            exception = std::current_exception();
        }
    }
};

// The text cut for `threads` threads, each piece ending with the first LF at or after
// its bound (a CR LF is never cut): a first piece of 1/threads of the text, which this
// thread takes first, then pieces of a quarter of that (at least kParsePieceBytes), taken
// by whichever thread is free: a helper that starts late or runs slowly (its core
// shared) then holds up the merge by one small piece at most, not by half the text.
std::vector<Piece> cut(std::string_view text, unsigned threads) {
    const std::size_t share = std::max(kParsePieceBytes, text.size() / std::max(threads, 1U));
    const std::size_t step = std::max(kParsePieceBytes, share / 4);
    std::vector<Piece> pieces;
    std::size_t start = 0, bound = threads > 1 ? share : text.size();
    do {  // at least one piece, empty for an empty text
        std::size_t end =
            bound >= text.size() ? std::string_view::npos : text.find('\n', std::max(start, bound));
        end = end == std::string_view::npos ? text.size() : end + 1;
        Piece& piece = pieces.emplace_back();
        piece.text = text.substr(start, end - start);
        piece.reserve_for = start == 0 ? text : piece.text;
        start = end, bound += step;
    } while (start < text.size());
    return pieces;
}

// The pieces in file order into one scene: each piece's statements that must occur once,
// which all came before its first mistake, then that mistake, then its spheres and
// lights, their lines counted on from the pieces before (the first piece's lists taken
// as they are: no copy).
Scene merge(std::vector<Piece>& pieces) {
    SceneBuilder all;
    int offset = 0;
    std::vector<std::string_view> tokens;
    for (Piece& p : pieces) {
        for (const auto& [line, text] : p.once) {
            split_line(text, tokens);
            all.statement(statement_of(tokens[0], offset + line), tokens, offset + line);
        }
        if (p.failure) fail(offset + p.failure->line, p.failure->what);
        if (p.exception) std::rethrow_exception(p.exception);
        Scene& s = p.spheres_and_lights.scene;
        if (&p == &pieces.front()) {
            all.scene.spheres = std::move(s.spheres), all.scene.lights = std::move(s.lights);
        } else {
            for (SphereSpec& sphere : s.spheres)
                sphere.line += offset, all.scene.spheres.push_back(std::move(sphere));
            for (LightSpec& light : s.lights)
                light.line += offset, all.scene.lights.push_back(std::move(light));
            std::vector<SphereSpec>().swap(s.spheres);  // not needed past this: a lower peak
        }
        offset += p.lines;
    }
    all.check_complete();
    return std::move(all.scene);
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& file_name, unsigned threads) {
    // A UTF-8 byte-order mark, as some Windows editors write, is not part of the scene.
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    std::vector<Piece> parts = cut(text, threads);
    // The first piece on this thread, then every thread takes the next piece left.
    std::atomic<std::size_t> next{1};
    auto parse_pieces = [&] {
        for (std::size_t k; (k = next++) < parts.size();) parts[k].parse();
    };
    HelperPool::Job helpers;
    if (parts.size() > 1)
        helpers.start(std::min(threads, static_cast<unsigned>(parts.size())) - 1, parse_pieces);
    parts[0].parse();
    parse_pieces();
    helpers.finish();
    try {
        return merge(parts);
    } catch (const Failure& f) {
        throw SceneError(file_name, f.line, f.what);
    }
}

}  // namespace rt
