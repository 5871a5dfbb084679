// Scene-file parsing. One statement per line (ended by LF, CR LF or a lone CR): a
// keyword and a fixed number of fields, separated by spaces or tabs (\v and \f too;
// SPEC section 2). Reading line by line, rather than as one token stream, lets a short
// SPHERE line be reported on its own line; what each statement means and must hold is
// scene_statements.h's.
// A large text is cut into pieces at line starts, parsed at once on the helper threads
// and merged in file order (Piece, merge()): the same scene, and the same first mistake.
#include "raytracer/parser.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <optional>
#include <utility>
#include <vector>

#include "raytracer/helper_pool.h"
#include "raytracer/large_pages.h"
#include "raytracer/scene_error.h"
#include "raytracer/scene_lines.h"
#include "scene_statements.h"

namespace rt {
namespace {

using statements_of_scenes::fail;
using statements_of_scenes::Failure;
using statements_of_scenes::SceneBuilder;
using statements_of_scenes::Statement;
using statements_of_scenes::statement_of;

// The fewest bytes a SPHERE line takes: the keyword and 15 fields of one byte, each
// after a separator. So a text of b bytes declares at most b / 36 + 1 ellipsoids.
constexpr std::size_t kShortestSphereLine = 36;

// What a thread keeps from piece to piece: its buffers, and one list for the spheres
// of every piece but the first that it parses, each piece a range of it.
//
// WHY: few large lists, reserved once (Piece::reserve()), go on 2 MiB pages
// (large_pages.h), where a list per piece, reserved for its own bytes, took 4 KiB
// pages and a fault each: random 100k read and prepared, 6,400 faults and 121 ms
// against 2,900-3,600 and 87-90 ms.
struct PieceThread {
    std::vector<char> buffer;  // a file's chunk (file_pieces.h)
    LineTokens tokens;         // of the current line
    LargeVector<SphereSpec> spheres;
};

// A piece of the text, from a line's start to the next piece's, parsed on its own: its
// spheres and lights. The statements that must occur once are kept for the merge, which
// alone knows whether an earlier piece had one: so that a piece stops at the same
// first mistake as the whole file would. Nothing else carries from line to line.
struct Piece {
    std::string_view text;           // the piece in memory, or
    const FileAt* file = nullptr;    // bytes [first, end) of this file, read as parsed
    std::size_t first = 0, end = 0;  // (file_pieces.h)
    // The bytes whose spheres its list is reserved for, where the list is new: the whole
    // text for the first piece (the merge appends the others' to its list), the rest of
    // the text for the others (one thread may parse all of them).
    std::size_t reserve_for = 0;
    SceneBuilder spheres_and_lights;  // its lights, and the first piece's spheres
    // The other pieces' spheres: [spheres_from, spheres_to) of their thread's list.
    LargeVector<SphereSpec>* spheres = nullptr;
    std::size_t spheres_from = 0, spheres_to = 0;
    std::vector<std::pair<int, std::string>> once;  // each such line and its number
    int lines = 0;
    bool any_token = false;          // some line holds a token
    bool unread = false;             // a read of the file failed or came short
    std::optional<Failure> failure;  // the piece's first mistake: it stops there
    std::exception_ptr exception;    // anything else (out of memory), rethrown in the merge

    void parse(PieceThread& thread, bool first_piece) {
        LargeVector<SphereSpec>& list = spheres_and_lights.scene.spheres;
        if (!first_piece) list.swap(thread.spheres), spheres = &thread.spheres, spheres_from = list.size();
        try {
            auto whole_lines = [&](std::string_view chunk) {
                if (list.capacity() == 0) reserve(list, chunk);
                for (std::string_view rest = chunk; !rest.empty();) {
                    ++lines;
                    const std::size_t line_end = split_line(rest, thread.tokens);
                    // A NUL byte never occurs in a text file; say so rather than "unknown keyword".
                    if (line_end == std::string_view::npos)
                        fail(lines, "a NUL byte (a binary file?), expected a text scene file");
                    if (!thread.tokens.empty()) {  // blank lines are allowed anywhere
                        any_token = true;
                        const Statement& s = statement_of(thread.tokens[0], lines);
                        if (s.required_once)
                            once.emplace_back(lines, rest.substr(0, line_end));
                        else
                            spheres_and_lights.statement(s, thread.tokens, lines);
                    }
                    rest.remove_prefix(next_line(rest, line_end));
                }
            };
            if (file == nullptr)
                whole_lines(text);
            else
                unread = !file->read_lines(first, end, thread.buffer, whole_lines);
        } catch (Failure& f) {
            any_token = true;  // a mistake is never in blank lines
            failure = std::move(f);
        } catch (...) {
            exception = std::current_exception();
        }
        if (!first_piece) spheres_to = list.size(), list.swap(thread.spheres);
    }

    // The list reserved, so that it is not copied as it grows (nor its peak twice its
    // size): for one sphere per "SPHERE" in the sample (the piece's first chunk, the
    // text not being at hand for a file), scaled to reserve_for bytes, and an eighth
    // more; a list that outgrows it is copied, as any vector. (Reserved for the most
    // those bytes can hold, kShortestSphereLine, it took 4 times the address space.)
    void reserve(LargeVector<SphereSpec>& list, std::string_view sample) const {
        sample = sample.substr(0, FileAt::kChunkBytes);
        std::size_t spheres = 0;
        for (std::size_t at = sample.find("SPHERE"); at != std::string_view::npos;
             at = sample.find("SPHERE", at + 6))
            ++spheres;
        if (sample.size() < reserve_for) {
            const double scaled = double(spheres) * (double(reserve_for) / double(sample.size())) * 1.125;
            spheres = std::min(reserve_for / kShortestSphereLine + 1, static_cast<std::size_t>(scaled));
        }
        list.reserve(spheres);
    }
};

// Where the text of `size` bytes is cut for `threads` threads: each piece ends with
// the first LF at or after its bound (a CR LF is never cut), after_line_feed(bound): a
// first piece of 1/threads of the text, which this thread takes first, then pieces of
// a quarter of that (at least kParsePieceBytes), taken by whichever thread is free: a
// helper that starts late or runs slowly (its core shared) then holds up the merge by
// one small piece at most, not by half the text. Piece k is [starts[k], starts[k + 1]).
template <typename AfterLineFeed>
std::vector<std::size_t> cut(std::size_t size, unsigned threads, AfterLineFeed after_line_feed) {
    const std::size_t share = std::max(kParsePieceBytes, size / std::max(threads, 1U));
    const std::size_t step = std::max(kParsePieceBytes, share / 4);
    std::vector<std::size_t> starts{0};
    for (std::size_t bound = threads > 1 ? share : size;; bound += step) {
        const std::size_t end = bound >= size ? size : after_line_feed(std::max(starts.back(), bound));
        starts.push_back(end);
        if (end >= size) return starts;  // at least one piece, empty for an empty text
    }
}

// The pieces [starts[k], starts[k + 1]) of a text of starts.back() bytes, and the
// threads that parse them (at most one a piece), each piece with its list's
// reserve_for: the whole text for the first piece; for the others, the rest of the text
// shared by the threads that parse it (all of them but the one that starts with the
// first piece, which may join).
struct Pieces {
    std::vector<Piece> parts;
    std::vector<PieceThread> threads;
};
Pieces pieces_of(const std::vector<std::size_t>& starts, unsigned threads) {
    Pieces pieces{std::vector<Piece>(starts.size() - 1),
                  std::vector<PieceThread>(std::min<std::size_t>(std::max(threads, 1U), starts.size() - 1))};
    const std::size_t rest =
        (starts.back() - starts[1]) / std::max<std::size_t>(pieces.threads.size() - 1, 1);
    for (std::size_t k = 0; k < pieces.parts.size(); ++k)
        pieces.parts[k].reserve_for = k == 0 ? starts.back() : rest;
    return pieces;
}

// The pieces parsed: the first on this thread, then each by whichever thread is free,
// the spheres of all but the first into their threads' lists (one per thread).
void parse_all(Pieces& pieces) {
    std::vector<Piece>& parts = pieces.parts;
    std::atomic<std::size_t> next{1}, next_thread{0};
    // From piece k on, then each next piece left.
    auto parse_pieces = [&](std::size_t k) {
        PieceThread& thread = pieces.threads[next_thread++];
        for (; k < parts.size(); k = next++) parts[k].parse(thread, k == 0);
    };
    auto helper = [&] { parse_pieces(next++); };
    HelperPool::Job helpers;
    if (parts.size() > 1) helpers.start(static_cast<unsigned>(pieces.threads.size()) - 1, helper);
    parse_pieces(0);
    helpers.finish();
}

// The pieces in file order into one scene: each piece's statements that must occur once,
// which all came before its first mistake, then that mistake, then its spheres and
// lights, their lines counted on from the pieces before (the first piece's lists taken
// as they are: no copy; a thread's list freed after its last piece, for a lower peak).
// A mistake is thrown as file_name's SceneError.
Scene merge(std::vector<Piece>& pieces, const std::string& file_name) {
    std::vector<bool> last_of_list(pieces.size());
    std::vector<const LargeVector<SphereSpec>*> seen;
    for (std::size_t k = pieces.size(); k-- > 1;) {
        const LargeVector<SphereSpec>* list = pieces[k].spheres;
        last_of_list[k] = list != nullptr && std::find(seen.begin(), seen.end(), list) == seen.end();
        if (last_of_list[k]) seen.push_back(list);
    }
    SceneBuilder all;
    int offset = 0;
    LineTokens tokens;
    try {
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            Piece& p = pieces[k];
            for (const auto& [line, text] : p.once) {
                split_line(text, tokens);
                all.statement(statement_of(tokens[0], offset + line), tokens, offset + line);
            }
            if (p.failure) fail(offset + p.failure->line, p.failure->what);
            if (p.exception) std::rethrow_exception(p.exception);
            Scene& s = p.spheres_and_lights.scene;
            if (k == 0) {
                all.scene.spheres = std::move(s.spheres), all.scene.lights = std::move(s.lights);
            } else {
                for (std::size_t i = p.spheres_from; i < p.spheres_to; ++i) {
                    all.scene.spheres.push_back((*p.spheres)[i]);
                    all.scene.spheres.back().line += offset;
                }
                if (last_of_list[k]) LargeVector<SphereSpec>().swap(*p.spheres);
                for (LightSpec light : s.lights) light.line += offset, all.scene.lights.push_back(light);
            }
            offset += p.lines;
        }
        all.check_complete();
    } catch (const Failure& f) {
        throw SceneError(file_name, f.line, f.what);
    }
    return std::move(all.scene);
}

}  // namespace

// A small text is one piece, parsed on this thread: Piece::parse() line by line (the
// spheres and lights), then merge() applies the statements that occur once (NEAR ...
// OUTPUT) and checks the scene as a whole.
Scene parse_scene(std::string_view text, const std::string& file_name, unsigned threads) {
    // A UTF-8 byte-order mark, as some Windows editors write, is not part of the scene.
    if (text.substr(0, 3) == kUtf8Mark) text.remove_prefix(3);
    const std::vector<std::size_t> starts = cut(text.size(), threads, [text](std::size_t at) {
        const std::size_t lf = text.find('\n', at);
        return lf == std::string_view::npos ? text.size() : lf + 1;
    });
    Pieces pieces = pieces_of(starts, threads);
    for (std::size_t k = 0; k < pieces.parts.size(); ++k)
        pieces.parts[k].text = text.substr(starts[k], starts[k + 1] - starts[k]);
    parse_all(pieces);
    return merge(pieces.parts, file_name);
}

std::optional<Scene> parse_scene_file(const FileAt& file, const std::string& file_name, unsigned threads) {
    char mark[3] = {};
    const std::size_t marked = std::min<std::size_t>(3, file.size());
    if (!file.read(0, marked, mark)) return std::nullopt;
    if (is_utf16(std::string_view(mark, marked))) throw SceneError(file_name, 0, kUtf16Text);
    const bool utf8_mark = std::string_view(mark, marked) == kUtf8Mark;
    bool unread = false;
    std::vector<std::size_t> starts = cut(file.size(), threads, [&](std::size_t at) {
        const std::optional<std::size_t> next = file.after_line_feed(at);
        unread = unread || !next;
        return next.value_or(file.size());
    });
    if (unread) return std::nullopt;
    Pieces pieces = pieces_of(starts, threads);
    std::vector<Piece>& parts = pieces.parts;
    for (std::size_t k = 0; k < parts.size(); ++k)
        parts[k].file = &file, parts[k].first = starts[k], parts[k].end = starts[k + 1];
    if (utf8_mark) parts[0].first = std::min<std::size_t>(3, starts[1]);  // not part of the scene
    parse_all(pieces);
    // A mark alone is not an empty file, as in load_scene(); nor is one whose pieces all
    // ran out of memory before their first token (the merge throws that).
    bool any_token = utf8_mark;
    for (const Piece& p : parts)
        unread = unread || p.unread, any_token = any_token || p.any_token || p.exception != nullptr;
    if (unread || !file.ends_at_size()) return std::nullopt;
    if (!any_token) throw SceneError(file_name, 0, kEmptyFile);
    return merge(parts, file_name);
}

}  // namespace rt
