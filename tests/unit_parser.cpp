// The scene parser: layouts the course files use, number forms, and the first
// mistake reported on its own line.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#ifdef __linux__
#include <sys/resource.h>
#include <unistd.h>
#endif

#include "check.h"
#include "raytracer/compiler.h"
#include "raytracer/file_pieces.h"
#include "raytracer/parser.h"
#include "raytracer/scene_error.h"
#include "raytracer/scene_lines.h"

namespace {

const char* const kMinimal =
    "NEAR 1\nLEFT -1\nRIGHT 1\nBOTTOM -1\nTOP 1\nRES 4 3\n"
    "SPHERE s1 0 0 -10 2 4 2 0.5 0 0 1 1 0.9 0 50\n"
    "LIGHT l1 0 0 0 0.9 0.9 0.9\n"
    "BACK 1 1 1\nAMBIENT 0.2 0.2 0.2\nOUTPUT out.ppm\n";

// The message of the SceneError that parsing text throws, or "" if it parses.
std::string error_of(const std::string& text) {
    try {
        rt::parse_scene(text, "scene.txt");
    } catch (const rt::SceneError& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// text with one line (1-based) replaced, e.g. to make a single mistake.
std::string replace_line(std::string text, int line, const std::string& replacement) {
    std::size_t start = 0;
    for (int i = 1; i < line; ++i) start = text.find('\n', start) + 1;
    const std::size_t end = text.find('\n', start);
    return text.replace(start, end - start, replacement);
}

std::string with_line(int line, const std::string& replacement) {
    return replace_line(kMinimal, line, replacement);
}

}  // namespace

// Every field a value of its own, so that two fields read into each other's place show.
TEST(reads_every_field) {
    const rt::Scene s = rt::parse_scene(
        "NEAR 1.5\nLEFT -1.25\nRIGHT 1.75\nBOTTOM -0.5\nTOP 0.75\nRES 4 3\n"
        "SPHERE s1 1 2 -10 3 4 5 0.1 0.2 0.3 0.4 0.5 0.6 0.7 50\n"
        "LIGHT l1 6 7 8 0.11 0.12 0.13\n"
        "BACK 0.21 0.22 0.23\nAMBIENT 0.31 0.32 0.33\nOUTPUT out.ppm\n",
        "scene.txt");
    auto is = [](const rt::Vec3<double>& v, double x, double y, double z) {
        return v.x == x && v.y == y && v.z == z;
    };
    CHECK_EQ(s.near_plane, 1.5);
    CHECK_EQ(s.left, -1.25);
    CHECK_EQ(s.right, 1.75);
    CHECK_EQ(s.bottom, -0.5);
    CHECK_EQ(s.top, 0.75);
    CHECK_EQ(s.columns, 4);
    CHECK_EQ(s.rows, 3);
    CHECK_EQ(s.spheres.size(), 1U);
    const rt::SphereSpec& sp = s.spheres[0];
    CHECK(is(sp.centre, 1, 2, -10));
    CHECK(is(sp.scale, 3, 4, 5));
    CHECK(is(sp.colour, 0.1, 0.2, 0.3));
    CHECK_EQ(sp.ka, 0.4);
    CHECK_EQ(sp.kd, 0.5);
    CHECK_EQ(sp.ks, 0.6);
    CHECK_EQ(sp.kr, 0.7);
    CHECK_EQ(sp.shininess, 50.0);
    CHECK_EQ(sp.line, 7);
    CHECK_EQ(s.lights.size(), 1U);
    CHECK(is(s.lights[0].position, 6, 7, 8));
    CHECK(is(s.lights[0].intensity, 0.11, 0.12, 0.13));
    CHECK_EQ(s.lights[0].line, 8);
    CHECK(is(s.background, 0.21, 0.22, 0.23));
    CHECK(is(s.ambient, 0.31, 0.32, 0.33));
    CHECK_EQ(s.output, std::string("out.ppm"));
    CHECK_EQ(s.output_line, 11);
}

// testParsing.txt's layout: OUTPUT first, tabs and "space + tab" separators, blank
// lines, keywords in another order, and a file ending in "\n\n".
TEST(accepts_tabs_blank_lines_and_any_order) {
    const std::string text =
        "\nOUTPUT \ttestParsing.ppm\n\nLEFT\t\t-1\nRIGHT\t\t1\nBOTTOM\t-1\nTOP\t\t1\nNEAR \t\t1\n\n"
        "AMBIENT\t0.2\t0.2\t0.2\nBACK \t\t1 \t1 \t1\n\nRES\t\t600 \t600\n\n"
        "SPHERE\ts1\t0\t0\t-10\t2\t4\t2\t0.5\t0\t0\t1\t1\t0.9\t0\t50\n\n"
        "LIGHT\t\tl1\t0\t0\t0\t0.9\t0.9\t0.9\n\n";
    const rt::Scene s = rt::parse_scene(text, "testParsing.txt");
    CHECK_EQ(s.output, std::string("testParsing.ppm"));
    CHECK_EQ(s.near_plane, 1.0);
    CHECK_EQ(s.columns, 600);
    CHECK_EQ(s.spheres.size(), 1U);
    CHECK_EQ(s.spheres[0].line, 15);
    CHECK_EQ(s.lights.size(), 1U);
}

TEST(accepts_a_last_line_without_newline) {
    std::string text = kMinimal;
    text.pop_back();
    CHECK_EQ(rt::parse_scene(text, "scene.txt").output, std::string("out.ppm"));
}

TEST(accepts_crlf_line_ends) {
    std::string text;
    for (const char c : std::string(kMinimal)) {
        if (c == '\n') text += '\r';
        text += c;
    }
    const rt::Scene s = rt::parse_scene(text, "scene.txt");
    CHECK_EQ(s.output, std::string("out.ppm"));  // no stray CR in the name
    CHECK_EQ(s.columns, 4);
}

TEST(accepts_every_decimal_form) {
    const rt::Scene s =
        rt::parse_scene(with_line(7, "SPHERE s -4 .5 +2 1e-3 2.5E+1 7. 0 0 0 0 0 0 0 10.5"), "x");
    CHECK_EQ(s.spheres[0].centre.x, -4.0);
    CHECK_EQ(s.spheres[0].centre.y, 0.5);
    CHECK_EQ(s.spheres[0].centre.z, 2.0);
    CHECK_EQ(s.spheres[0].scale.x, 0.001);
    CHECK_EQ(s.spheres[0].scale.y, 25.0);
    CHECK_EQ(s.spheres[0].scale.z, 7.0);
    CHECK_EQ(s.spheres[0].shininess, 10.5);
}

// Every decimal form reads to the double strtod gives, bit for bit: random signs,
// digit counts up to 25 (past double's 17), leading and trailing points, exponents
// from -340 to 330 (denormals, underflow to 0; overflow is refused), leading zeros.
TEST(numbers_read_as_strtod_reads_them) {
    std::mt19937 g(5);
    auto digits = [&](int n) {
        std::string d;
        for (int i = 0; i < n; ++i) d += static_cast<char>('0' + g() % 10);
        return d;
    };
    int checked = 0;
    for (int k = 0; k < 20000; ++k) {
        std::string t = g() % 4 == 0 ? "-" : g() % 8 == 0 ? "+" : "";
        const int whole = static_cast<int>(g() % 12), fraction = static_cast<int>(g() % 14);
        t += digits(whole);
        if (fraction > 0 || whole == 0 || g() % 4 == 0)
            t += "." + digits(whole == 0 ? fraction + 1 : fraction);
        if (g() % 2 == 0) t += (g() % 2 ? "e" : "E") + std::to_string(static_cast<int>(g() % 671) - 340);
        const double expected = std::strtod(t.c_str(), nullptr);
        if (!(expected - expected == 0)) continue;  // overflow: refused, checked elsewhere
        const rt::Scene s =
            rt::parse_scene(with_line(7, "SPHERE s " + t + " 0 0 1 1 1 0 0 0 0 0 0 0 1"), "x");
        const double got = s.spheres[0].centre.x;
        std::uint64_t a = 0, b = 0;
        std::memcpy(&a, &got, sizeof a), std::memcpy(&b, &expected, sizeof b);
        if (a != b) std::cerr << "'" << t << "' read as " << got << ", strtod gives " << expected << "\n";
        CHECK(a == b);
        ++checked;
    }
    CHECK(checked > 15000);
}

TEST(spheres_and_lights_are_optional_and_unlimited) {
    const rt::Scene empty = rt::parse_scene(replace_line(with_line(7, ""), 8, ""), "x");
    CHECK_EQ(empty.spheres.size(), 0U);
    CHECK_EQ(empty.lights.size(), 0U);
    std::string many = kMinimal;
    for (int i = 0; i < 40; ++i) many += "SPHERE s 0 0 -5 1 1 1 1 1 1 1 1 1 0 1\nLIGHT l 0 0 0 1 1 1\n";
    const rt::Scene big = rt::parse_scene(many, "x");
    CHECK_EQ(big.spheres.size(), 41U);
    CHECK_EQ(big.lights.size(), 41U);
}

TEST(a_short_sphere_line_is_reported_on_its_own_line) {
    const std::string e = error_of(with_line(7, "SPHERE s1 0 0 -10 2 4 2 0.5 0 0 1 1 0.9 0"));
    CHECK(contains(e, "scene.txt:7: error: SPHERE has 14 fields, expected 15"));
}

TEST(reports_an_unknown_keyword) {
    const std::string e = error_of(with_line(8, "LAMP l1 0 0 0 1 1 1"));
    CHECK(contains(e, "scene.txt:8: error: unknown keyword 'LAMP'"));
}

TEST(reports_malformed_and_non_finite_numbers) {
    CHECK(
        contains(error_of(with_line(1, "NEAR 0.5x")), "scene.txt:1: error: NEAR <n> is '0.5x', expected a"));
    CHECK(contains(error_of(with_line(1, "NEAR nan")), "scene.txt:1:"));
    CHECK(contains(error_of(with_line(1, "NEAR inf")), "scene.txt:1:"));
    CHECK(contains(error_of(with_line(1, "NEAR 1e999")), "scene.txt:1:"));
    CHECK(contains(error_of(with_line(1, "NEAR 0x10")), "scene.txt:1:"));
    CHECK(contains(error_of(with_line(1, "NEAR .")), "scene.txt:1:"));
    CHECK(contains(error_of(with_line(1, "NEAR 1e")), "scene.txt:1:"));
}

TEST(reports_bad_resolutions) {
    CHECK(contains(error_of(with_line(6, "RES 0 3")),
                   "scene.txt:6: error: RES <x> is '0', expected a positive"));
    CHECK(contains(error_of(with_line(6, "RES 4 -3")), "scene.txt:6:"));
    CHECK(contains(error_of(with_line(6, "RES 4.5 3")), "scene.txt:6:"));
    CHECK(contains(error_of(with_line(6, "RES 99999999999999999999999 3")), "scene.txt:6:"));
    CHECK(contains(error_of(with_line(6, "RES 100000 100000")),
                   "scene.txt:6: error: RES 100000 100000 is too large"));
}

TEST(reports_missing_and_repeated_keywords) {
    CHECK_EQ(error_of(""), std::string("scene.txt: error: no NEAR line, expected exactly one: NEAR <n>"));
    CHECK_EQ(error_of("\xEF\xBB\xBF"), error_of(""));
    // Each once-only statement of kMinimal left out in turn.
    const std::pair<int, const char*> once[] = {{1, "NEAR"},   {2, "LEFT"},     {3, "RIGHT"},
                                                {4, "BOTTOM"}, {5, "TOP"},      {6, "RES"},
                                                {9, "BACK"},   {10, "AMBIENT"}, {11, "OUTPUT"}};
    for (const auto& [line, keyword] : once)
        CHECK(contains(error_of(with_line(line, "")),
                       std::string("scene.txt: error: no ") + keyword + " line, expected exactly one"));
    CHECK(contains(error_of(with_line(11, "NEAR 2")),
                   "scene.txt:11: error: a second NEAR (the first is on line 1)"));
}

TEST(reports_meaningless_values) {
    CHECK(contains(error_of(with_line(1, "NEAR 0")),
                   "scene.txt:1: error: NEAR is 0, expected a distance greater"));
    CHECK(contains(error_of(with_line(1, "NEAR -1")), "scene.txt:1:"));
    CHECK(contains(error_of(with_line(3, "RIGHT -1")),
                   "scene.txt:3: error: LEFT -1 and RIGHT -1, expected LEFT < RIGHT"));
    CHECK(contains(error_of(with_line(5, "TOP -2")), "scene.txt:5: error: BOTTOM -1 and TOP -2"));
    CHECK(contains(error_of(with_line(7, "SPHERE s1 0 0 -10 2 0 2 0.5 0 0 1 1 0.9 0 50")),
                   "scene.txt:7: error: SPHERE 's1' <scl y> is '0', expected a non-zero scale"));
    CHECK(
        contains(error_of(with_line(11, "OUTPUT")), "scene.txt:11: error: OUTPUT has 0 fields, expected 1"));
}

TEST(values_outside_0_1_are_kept_as_given) {
    const rt::Scene s = rt::parse_scene(with_line(8, "LIGHT l1 0 0 0 2.5 -1 7"), "x");
    CHECK_EQ(s.lights[0].intensity.x, 2.5);
    CHECK_EQ(s.lights[0].intensity.y, -1.0);
}

namespace {

// A text large enough to be cut into pieces (parser.h): kMinimal's lines, then spheres
// and lights, as lines to edit; joined with `end` between lines.
std::vector<std::string> many_lines(std::size_t count = 30000) {
    std::vector<std::string> lines;
    for (std::size_t at = 0, next; (next = std::string(kMinimal).find('\n', at)) != std::string::npos;
         at = next + 1)
        lines.push_back(std::string(kMinimal).substr(at, next - at));
    for (int i = 0; lines.size() < count; ++i) {
        lines.push_back("SPHERE s" + std::to_string(i) + " " + std::to_string(i % 17) +
                        ".25 -1.5e-3 -10 0.5 2 1.125 0.5 0 1 1 0.9 0.25 0.125 50");
        if (i % 1000 == 0) lines.push_back("LIGHT l" + std::to_string(i) + " 0 1e2 -3 0.9 0.5 0.25");
        if (i % 3000 == 0) lines.emplace_back();
    }
    return lines;
}

std::string joined(const std::vector<std::string>& lines, const char* end = "\n") {
    std::string text;
    for (const std::string& line : lines) text += line + end;
    return text;
}

// The message parsing text on `threads` threads throws, or "" if it parses.
std::string error_in(const std::string& text, unsigned threads) {
    try {
        rt::parse_scene(text, "big.txt", threads);
    } catch (const rt::SceneError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(pieces_give_the_scene_of_one_piece) {
    std::vector<std::string> lines = many_lines();
    std::swap(lines[10], lines.back());  // OUTPUT in the last piece, a sphere line in the first
    for (const char* end : {"\n", "\r\n", "\r"}) {
        const std::string text = joined(lines, end);
        CHECK(text.size() >= 3 * rt::kParsePieceBytes);
        const rt::Scene one = rt::parse_scene(text, "big.txt", 1);
        CHECK_EQ(one.output_line, static_cast<int>(lines.size()));
        for (unsigned threads : {2U, 3U, 16U}) {  // 6, 7 and 9 pieces
            const rt::Scene s = rt::parse_scene(text, "big.txt", threads);
            CHECK_EQ(s.spheres.size(), one.spheres.size());
            CHECK_EQ(s.lights.size(), one.lights.size());
            for (std::size_t i = 0; i < s.spheres.size() && i < one.spheres.size(); ++i) {
                const rt::SphereSpec &a = s.spheres[i], &b = one.spheres[i];
                CHECK(a.line == b.line && a.centre.x == b.centre.x && a.centre.y == b.centre.y &&
                      a.scale.z == b.scale.z && a.colour.y == b.colour.y && a.kr == b.kr &&
                      a.shininess == b.shininess);
            }
            for (std::size_t i = 0; i < s.lights.size() && i < one.lights.size(); ++i)
                CHECK(s.lights[i].line == one.lights[i].line &&
                      s.lights[i].position.y == one.lights[i].position.y);
            CHECK(s.output == one.output && s.output_line == one.output_line && s.columns == one.columns &&
                  s.near_plane == one.near_plane && s.ambient.x == one.ambient.x);
        }
    }
}

// The first mistake in file order, on its line, whatever the pieces: in the second
// half, in both halves, and a second once-only statement whose first is in another
// piece (where a line both repeats NEAR and holds a bad number, the repeat is reported,
// as in one piece; a wrong field count is found first).
TEST(pieces_report_the_first_mistake_of_one_piece) {
    const std::vector<std::string> base = many_lines();
    const std::size_t late = base.size() * 3 / 4, early = base.size() / 4;
    const std::string bad_sphere = "SPHERE bad 0 0 -10 1 0 1 1 1 1 1 1 1 0 5";
    struct Case {
        std::vector<std::pair<std::size_t, std::string>> edits;
        std::string expected;  // the message of one piece, in part
    };
    const std::string late_line = ":" + std::to_string(late + 1) + ": error: ";
    const std::vector<Case> cases = {
        {{{late, bad_sphere}}, late_line + "SPHERE 'bad' <scl y> is '0'"},
        {{{late, bad_sphere}, {early, "LAMP"}}, ":" + std::to_string(early + 1) + ": error: unknown keyword"},
        {{{late, "NEAR 2"}}, late_line + "a second NEAR (the first is on line 1)"},
        {{{late, "NEAR x"}}, late_line + "a second NEAR"},
        {{{late, "NEAR"}}, late_line + "NEAR has 0 fields"},
        {{{late, "RES 2 2"}, {late + 1, "RES 3 3"}}, late_line + "a second RES (the first is on line 6)"},
        {{{late, bad_sphere}, {late + 1, "NEAR 2"}}, late_line + "SPHERE 'bad'"},
        {{{late, "NEAR 2"}, {late + 1, bad_sphere}}, late_line + "a second NEAR"},
        {{{late, std::string("SPHERE \0", 8)}}, late_line + "a NUL byte"},
        {{{0, ""}, {late, "NEAR 0"}}, late_line + "NEAR is 0"},
        {{{2, ""}, {late, "RIGHT -1"}}, late_line + "LEFT -1 and RIGHT -1"},
        // A window's mistake shows on the later line of its pair, before a later mistake.
        {{{2, ""}, {early, "RIGHT -2"}, {late, bad_sphere}},
         ":" + std::to_string(early + 1) + ": error: LEFT -1 and RIGHT -2"},
        {{{10, ""}}, "big.txt: error: no OUTPUT line"},
        {{{0, "NEAR 0"}, {late, bad_sphere}}, "big.txt:1: error: NEAR is 0"},
        {{{early, bad_sphere}, {late, "NEAR 2"}}, ":" + std::to_string(early + 1) + ": error: SPHERE 'bad'"},
        {{{0, ""}, {late, "NEAR 1"}, {late + 1, "NEAR 2"}},
         ":" + std::to_string(late + 2) + ": error: a second NEAR (the first is on line " +
             std::to_string(late + 1) + ")"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> lines = base;
        for (const auto& [line, text] : c.edits) lines[line] = text;
        const std::string text = joined(lines);
        const std::string one = error_in(text, 1);
        if (!contains(one, c.expected)) std::cerr << "expected '" << c.expected << "', got: " << one << "\n";
        CHECK(contains(one, c.expected));
        for (unsigned threads : {2U, 3U, 7U}) {
            const std::string got = error_in(text, threads);
            if (got != one) std::cerr << threads << " threads: " << got << "\n    one piece: " << one << "\n";
            CHECK_EQ(got, one);
        }
    }
}

namespace {

// Whether two scenes hold the same statements, field for field.
bool same_scene(const rt::Scene& a, const rt::Scene& b) {
    auto same_vec = [](const rt::Vec3<double>& x, const rt::Vec3<double>& y) {
        return x.x == y.x && x.y == y.y && x.z == y.z;
    };
    bool same = a.spheres.size() == b.spheres.size() && a.lights.size() == b.lights.size() &&
                a.output == b.output && a.output_line == b.output_line && a.columns == b.columns &&
                a.rows == b.rows && a.near_plane == b.near_plane && a.left == b.left && a.right == b.right &&
                a.bottom == b.bottom && a.top == b.top && same_vec(a.ambient, b.ambient) &&
                same_vec(a.background, b.background);
    for (std::size_t i = 0; same && i < a.spheres.size(); ++i) {
        const rt::SphereSpec &x = a.spheres[i], &y = b.spheres[i];
        same = x.line == y.line && same_vec(x.centre, y.centre) && same_vec(x.scale, y.scale) &&
               same_vec(x.colour, y.colour) && x.ka == y.ka && x.kd == y.kd && x.ks == y.ks && x.kr == y.kr &&
               x.shininess == y.shininess;
    }
    for (std::size_t i = 0; same && i < a.lights.size(); ++i) {
        const rt::LightSpec &x = a.lights[i], &y = b.lights[i];
        same = x.line == y.line && same_vec(x.position, y.position) && same_vec(x.intensity, y.intensity);
    }
    return same;
}

// A file of its own in the temporary folder, removed however the test ends.
struct TempFile {
    std::filesystem::path path;
    explicit TempFile(const std::string& bytes) {
        std::random_device random;
        path = std::filesystem::temp_directory_path() /
               ("raytracer-unit-parser-" + std::to_string(random()) + std::to_string(random()) + ".txt");
        write(bytes);
    }
    ~TempFile() {
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
    }
    void write(const std::string& bytes) const {
        std::ofstream out(path, std::ios::binary);
        out << bytes;
    }
};

}  // namespace

// FileAt::read_lines() (file_pieces.h) gives bytes [first, end) of the file in order,
// each chunk ending after a line end (never between the CR and LF of a CR LF) or at
// end, also for lines longer than a chunk; after_line_feed() finds the next line; a
// size the file does not have (it changed since its size was taken) fails. The
// handle's position stays where it was.
TEST(file_at_reads_whole_lines_in_order) {
    std::mt19937 random(3);
    std::string bytes(3 * rt::FileAt::kChunkBytes + 12345, ' ');
    for (char& c : bytes) c = "ab \r\n\0\xFF"[random() % 7];
    for (std::size_t k = 0; k < rt::FileAt::kChunkBytes + 99; ++k) bytes[1000 + k] = 'x';  // a long line
    const TempFile file(bytes);
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.path.string().c_str(), "rb"),
                                                             &std::fclose);
    CHECK(in != nullptr);
    if (!in) return;
    const rt::FileAt at(in.get(), bytes.size());
    std::vector<char> buffer;
    for (const auto& range :
         std::vector<std::pair<std::size_t, std::size_t>>{{0, bytes.size()},
                                                          {1000, 2000},
                                                          {999, bytes.size() - 1},
                                                          {5, 5},
                                                          {bytes.size() - 3, bytes.size()}}) {
        const std::size_t first = range.first, end = range.second;
        std::string got;
        bool whole = true;
        const bool read = at.read_lines(first, end, buffer, [&](std::string_view chunk) {
            const std::size_t chunk_end = first + got.size() + chunk.size();
            const char last = chunk.back();
            whole = whole && (chunk_end == end || last == '\n' || (last == '\r' && bytes[chunk_end] != '\n'));
            got += chunk;
        });
        CHECK_EQ(read, rt::kReadsInPieces || first == end);  // nothing to read: nothing fails
        if (!rt::kReadsInPieces) continue;
        CHECK(whole);
        CHECK(got == bytes.substr(first, end - first));
    }
    if (rt::kReadsInPieces) {
        for (std::size_t from : {std::size_t{0}, std::size_t{1000}, bytes.size() - 2}) {
            const std::size_t lf = bytes.find('\n', from);
            CHECK(at.after_line_feed(from) == (lf == std::string::npos ? bytes.size() : lf + 1));
        }
        CHECK(at.ends_at_size());
        CHECK(!rt::FileAt(in.get(), bytes.size() - 1).ends_at_size());  // more follows
        const rt::FileAt longer(in.get(), bytes.size() + 1);            // short
        CHECK(!longer.read_lines(0, longer.size(), buffer, [](std::string_view) {}));
    }
    CHECK_EQ(std::ftell(in.get()), 0L);
}

// regular_file_size() (file_pieces.h) asks the open file, not its name: a file renamed
// over the name since changes nothing (POSIX; Windows refuses to rename over an open
// file). Nothing but a regular file has a size: a folder has none.
TEST(a_file_size_is_the_open_files) {
    const TempFile opened(std::string(1000, 'a')), other(std::string(70000, 'b'));
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(opened.path.string().c_str(), "rb"),
                                                             &std::fclose);
    CHECK(in != nullptr);
    if (!in) return;
    CHECK(rt::regular_file_size(in.get()) == std::optional<std::uintmax_t>(1000));
#ifndef _WIN32
    std::filesystem::rename(other.path, opened.path);
    CHECK_EQ(std::filesystem::file_size(opened.path), std::uintmax_t{70000});
    CHECK(rt::regular_file_size(in.get()) == std::optional<std::uintmax_t>(1000));
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> folder(
        std::fopen(std::filesystem::temp_directory_path().string().c_str(), "rb"), &std::fclose);
    if (folder) CHECK(!rt::regular_file_size(folder.get()).has_value());  // Linux opens a folder
#endif
}

// parse_scene_file() gives what reading the whole text gives: the scene, for any line
// ends, byte-order mark and number of pieces; the first mistake on its line; an empty
// and a UTF-16 text refused as load_scene() refuses them.
TEST(a_file_parsed_as_read_gives_the_scene_of_its_text) {
    std::vector<std::string> lines = many_lines();
    std::swap(lines[10], lines.back());
    auto expected = [](const std::string& text) {  // load_scene() of a small file
        if (text.find_first_not_of(" \t\r\n\v\f") == std::string::npos) return std::string(rt::kEmptyFile);
        if (rt::is_utf16(text)) return std::string(rt::kUtf16Text);
        try {
            rt::parse_scene(text, "big.txt", 1);
        } catch (const rt::SceneError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    std::vector<std::string> texts;
    for (const char* end : {"\n", "\r\n", "\r"}) texts.push_back(joined(lines, end));
    texts.push_back(std::string(rt::kUtf8Mark) + texts[0]);
    std::vector<std::string> bad = lines;
    bad[bad.size() * 3 / 4] = "SPHERE bad 0 0 -10 1 0 1 1 1 1 1 1 1 0 5";
    texts.push_back(joined(bad, "\r\n"));
    bad[bad.size() / 2] = std::string("NEAR \0", 6);
    texts.push_back(joined(bad));
    texts.push_back(std::string(3 * rt::kParsePieceBytes, ' ') + "\n\r\n\t");
    texts.push_back(std::string(rt::kUtf8Mark) + texts.back());
    texts.push_back("\xFF\xFE" + texts[0]);
    for (const std::string& text : texts) {
        const TempFile file(text);
        const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.path.string().c_str(), "rb"),
                                                                 &std::fclose);
        CHECK(in != nullptr);
        if (!in || !rt::kReadsInPieces) continue;
        const std::string wanted = expected(text);
        for (unsigned threads : {1U, 2U, 3U, 16U}) {
            std::string message;
            try {
                const std::optional<rt::Scene> scene =
                    rt::parse_scene_file(rt::FileAt(in.get(), text.size()), "big.txt", threads);
                CHECK(scene.has_value());
                if (scene) CHECK(same_scene(*scene, rt::parse_scene(text, "big.txt", 1)));
            } catch (const rt::SceneError& e) {
                message = e.what();
            }
            CHECK(contains(message, wanted));
            CHECK_EQ(message.empty(), wanted.empty());
        }
        if (wanted.empty())  // it has grown since its size was taken
            CHECK(!rt::parse_scene_file(rt::FileAt(in.get(), text.size() - 1), "big.txt", 2));
    }
}

// A file large enough to be read in pieces (load_scene.cpp: 4 MiB, on a machine of two
// cores or more) reads as its text, and a mistake on its last line is reported there.
TEST(a_large_file_reads_as_its_text) {
    std::vector<std::string> lines = many_lines(60000);
    const std::string text = joined(lines);
    CHECK(text.size() >= (std::size_t{4} << 20));
    const TempFile file(text);
    const std::string path = file.path.string();
    try {
        CHECK(same_scene(rt::load_scene(path), rt::parse_scene(text, path, 1)));
    } catch (const rt::SceneError& e) {
        CHECK_EQ(std::string(e.what()), std::string());
    }
    lines.back() = "OUTPUT";
    file.write(joined(lines));
    std::string message;
    try {
        rt::load_scene(path);
    } catch (const rt::SceneError& e) {
        message = e.what();
    }
    CHECK(contains(message, ":" + std::to_string(lines.size()) + ": error: OUTPUT has 0 fields"));
}

// A file whose sphere list cannot be had is out of memory, not "empty": its pieces ran out
// before their first token. The address space is held to a few MiB above what the process
// maps (Linux; the sanitizers map terabytes), on one thread (no helper's stack to map).
#if defined(__linux__) && !defined(RT_SANITIZER_MAPS_TERABYTES)
TEST(a_file_read_out_of_memory_is_not_empty) {
    // Its list would take about 45 MB: more than earlier tests can have left free in the heap.
    const std::string text = joined(many_lines(260000));
    const TempFile file(text);
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.path.string().c_str(), "rb"),
                                                             &std::fclose);
    CHECK(in != nullptr);
    if (!in || !rt::kReadsInPieces) return;
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;  // the address space mapped, in pages
    rlimit was{};
    CHECK_EQ(getrlimit(RLIMIT_AS, &was), 0);
    const auto mapped = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE));
    const rlimit held{mapped + (rlim_t{4} << 20), was.rlim_max};
    CHECK(held.rlim_cur < was.rlim_cur);
    std::string outcome = "parsed";
    CHECK_EQ(setrlimit(RLIMIT_AS, &held), 0);
    try {
        (void)rt::parse_scene_file(rt::FileAt(in.get(), text.size()), "big.txt", 1);
    } catch (const std::bad_alloc&) {
        outcome = "out of memory";
    } catch (const rt::SceneError& e) {
        outcome = e.what();
    }
    CHECK_EQ(setrlimit(RLIMIT_AS, &was), 0);
    CHECK_EQ(outcome, std::string("out of memory"));
}
#endif

// split_line() (scene_lines.h) against a byte-by-byte reading of SPEC section 2, on
// random lines of every byte value: tokens of every length about the eight-byte words
// it skips, control and high bytes inside tokens, NUL and line ends anywhere.
TEST(split_line_matches_a_byte_by_byte_split) {
    auto separator = [](char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; };
    auto line_end = [](char c) { return c == '\n' || c == '\r'; };
    std::mt19937 random(7);
    const std::string common = "SPHERE 0.5e-3 -12 abc\x01\x7f\xc3\xa9";
    rt::LineTokens tokens;
    int mismatches = 0;
    for (int round = 0; round < 20000; ++round) {
        std::string line;
        const std::size_t length = round % 100 == 0 ? 2000 : random() % 48;  // past kKept tokens too
        for (std::size_t k = 0; k < length; ++k) {
            const unsigned pick = random() % 16;
            line += pick < 10   ? common[random() % common.size()]
                    : pick < 13 ? " \t\v\f"[random() % 4]
                    : pick < 15 ? static_cast<char>(random() % 256)
                                : "\n\r"[random() % 2];
        }
        std::vector<std::string_view> expected;
        std::size_t end = 0;
        const std::string_view text(line);
        for (std::size_t i = 0;;) {
            while (i < text.size() && separator(text[i])) ++i;
            if (i == text.size() || line_end(text[i])) {
                end = i;
                break;
            }
            if (text[i] == '\0') {
                end = std::string_view::npos;
                break;
            }
            const std::size_t start = i;
            while (i < text.size() && !separator(text[i]) && !line_end(text[i]) && text[i] != '\0') ++i;
            expected.push_back(text.substr(start, i - start));
        }
        const std::size_t got = rt::split_line(text, tokens);
        bool same = tokens.count == expected.size();
        for (std::size_t k = 0; same && k < std::min(expected.size(), rt::LineTokens::kKept); ++k)
            same = tokens[k] == expected[k];
        mismatches += got != end || (end != std::string_view::npos && !same);
    }
    CHECK_EQ(mismatches, 0);
}
