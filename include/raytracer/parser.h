// The scene-file reader: a hand-written, line-oriented parser that enforces every rule
// of SPEC section 2 and throws SceneError with the file and line of the first mistake.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "raytracer/file_pieces.h"
#include "raytracer/scene.h"

namespace rt {

// Images larger than this are refused before anything is allocated (3 bytes a pixel,
// so the largest image needs 300 MB). Each side is limited too, so that neither
// columns*rows nor any per-row arithmetic can overflow.
inline constexpr long long kMaxImagePixels = 100'000'000;
inline constexpr int kMaxImageSide = 100'000;

// A scene file is a few KB; one larger than this is not a scene file (or is an endless
// one such as /dev/zero) and is refused after reading this much, not read to the end.
inline constexpr std::size_t kMaxSceneFileBytes = std::size_t{64} << 20;

// Parses the text of a scene file; file_name is used only in messages. A text of over
// kParsePieceBytes is cut into pieces at line starts, parsed at once on up to `threads`
// threads (this one and helpers, helper_pool.h) and merged in file order: the same
// scene and the same first mistake as on one thread. A smaller piece costs more to
// start than it saves.
inline constexpr std::size_t kParsePieceBytes = std::size_t{256} << 10;
Scene parse_scene(std::string_view text, const std::string& file_name, unsigned threads = 1);

// The same for a scene file read as it is parsed, a chunk of whole lines at a time by
// the thread that parses it (file_pieces.h), for files too large to copy whole (and
// refused as load_scene() refuses an empty or UTF-16 text); nullopt where a read fails
// or comes short, or the file has grown: it changed while read. (A mistake found in
// bytes read before it changed is reported as such: the pieces stop at their first.)
std::optional<Scene> parse_scene_file(const FileAt& file, const std::string& file_name, unsigned threads);

// What load_scene() and parse_scene_file() say of a text that is not a scene's: an
// empty one (spaces, tabs, line ends) and a UTF-16 one (Windows editors may save it,
// its ASCII letters with NUL bytes between). A UTF-8 byte-order mark is skipped.
inline constexpr const char* kEmptyFile = "is empty, expected a scene file";
inline constexpr const char* kUtf16Text = "is UTF-16 text, expected ASCII or UTF-8 text";
inline constexpr std::string_view kUtf8Mark = "\xEF\xBB\xBF";
inline bool is_utf16(std::string_view text) {
    return text.rfind("\xFF\xFE", 0) == 0 || text.rfind("\xFE\xFF", 0) == 0;
}

// The scene file "-" is standard input, as -o - is standard output; messages call it
// <stdin>. (A file named "-" is read as ./-.)
inline constexpr std::string_view kStandardInput = "-";
inline std::string scene_name(const std::string& path) { return path == kStandardInput ? "<stdin>" : path; }

// Reads and parses a scene file (src/load_scene.cpp), on `threads` threads at most (0: as many as
// there are cores, as a render's --threads). Refuses what is not a scene file at all (missing,
// unreadable, a folder, too large, empty, UTF-16) with a SceneError that has no line.
Scene load_scene(const std::string& path, unsigned threads = 0);

}  // namespace rt
