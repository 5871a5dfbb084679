// Reading a scene file: what is not a scene file at all (missing, unreadable, a folder,
// too large, empty, UTF-16) is refused here, with no line; the text goes to parse_scene().
#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "raytracer/file_pieces.h"
#include "raytracer/helper_pool.h"
#include "raytracer/large_pages.h"
#include "raytracer/parser.h"
#include "raytracer/scene_error.h"

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#endif

namespace rt {

namespace {
// A file of at least this many bytes is parsed as it is read, in pieces on the helper
// threads too (file_pieces.h).
constexpr std::size_t kReadInPiecesBytes = std::size_t{4} << 20;

int keep_open(std::FILE* /*standard_input*/) { return 0; }  // read, not closed
}  // namespace

Scene load_scene(const std::string& path, unsigned threads_wanted) {
    const bool standard_input = path == kStandardInput;
    const std::string name = scene_name(path);
    // C stdio rather than an ifstream, and the open file asked for its size alone
    // unless it cannot be read: an ifstream's first use sets up locale facets, and
    // the status queries of cannot_read() cost system calls; together 0.1 ms of a 2 ms run.
    auto cannot_read = [&path, &name, standard_input](bool opened, int error) {
        const std::string cause = error != 0 ? std::string(": ") + std::strerror(error) : std::string();
        if (standard_input)  // closed when the program started: main() holds it open on a folder
            return SceneError(name, 0,
                              error == EISDIR ? "is closed (or a folder), expected a scene file"
                                              : "could not be read" + cause + ", expected a scene file");
        std::error_code ec;
        // Where a folder opens (Linux), reading it fails.
        if (std::filesystem::is_directory(path, ec))
            return SceneError(path, 0, "is a folder, expected a scene file");
        if (!opened && error == ENOENT) return SceneError(path, 0, "does not exist, expected a scene file");
        if (!opened && error == ENAMETOOLONG)
            return SceneError(path, 0, "is too long a name or path for the system, expected a scene file");
        if (!opened && error == EACCES)
            return SceneError(
                path, 0, "cannot be opened for reading: permission denied, expected a readable scene file");
        if (!opened && !std::filesystem::exists(path, ec) && !ec)  // ec: ELOOP, EACCES on the way
            return SceneError(path, 0, "does not exist, expected a scene file");
        return opened
                   ? SceneError(path, 0, "could not be read" + cause + ", expected a readable scene file")
                   : SceneError(path, 0,
                                "cannot be opened for reading" + cause + ", expected a readable scene file");
    };
#ifdef _WIN32
    if (standard_input) (void)_setmode(_fileno(stdin), _O_BINARY);  // read as a file is: "\r\n" kept
#endif
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(
        standard_input ? stdin : std::fopen(path.c_str(), "rb"), standard_input ? &keep_open : &std::fclose);
    if (!in) throw cannot_read(false, errno);
    const unsigned threads = std::min(threads_asked(threads_wanted), available_cores());
    const std::optional<std::uintmax_t> regular_size =
        standard_input ? std::nullopt : regular_file_size(in.get());  // standard input is read as a stream
    const std::uintmax_t size = regular_size.value_or(0);
    const bool size_known = regular_size.has_value();
    auto too_large = [&name] {
        return SceneError(
            name, 0,
            "is larger than " + std::to_string(kMaxSceneFileBytes >> 20) + " MiB, expected a scene file");
    };
    if (size_known && size > kMaxSceneFileBytes) throw too_large();  // refused before a byte is read
    // A large file of known size: parsed as read, in pieces; read again as a stream
    // where it changed meanwhile (the stream read starts where the handle is: at the start).
    if (kReadsInPieces && size_known && size >= kReadInPiecesBytes && size <= kMaxSceneFileBytes) {
        if (std::optional<Scene> scene =
                parse_scene_file(FileAt(in.get(), static_cast<std::size_t>(size)), name, threads))
            return std::move(*scene);
    }
    // Reserved at the file's size where the system tells it (one allocation, not a
    // doubling vector's: a 26 MB scene then peaks at 26 MB, not 48).
    LargeVector<char> bytes;
    if (size_known && size <= kMaxSceneFileBytes) bytes.reserve(static_cast<std::size_t>(size));
    char buffer[1 << 14];
    // Not read again past its end: a terminal's end (Ctrl-D) would then be asked for twice.
    for (std::size_t got;
         !std::feof(in.get()) && (got = std::fread(buffer, 1, sizeof buffer, in.get())) > 0;) {
        // A stream of unknown size (a pipe, /dev/zero) grows the buffer by doubling, but
        // never past the limit: at most 96 MiB while the last 32 are copied, not 192.
        if (bytes.size() + got > kMaxSceneFileBytes) throw too_large();
        if (bytes.size() + got > bytes.capacity())
            bytes.reserve(std::min(kMaxSceneFileBytes, std::max(2 * bytes.capacity(), bytes.size() + got)));
        bytes.insert(bytes.end(), buffer, buffer + got);
    }
    if (std::ferror(in.get()) != 0) throw cannot_read(true, errno);
    const std::string_view text(bytes.data(), bytes.size());
    if (text.find_first_not_of(" \t\r\n\v\f") == std::string_view::npos)
        throw SceneError(name, 0, kEmptyFile);
    if (is_utf16(text)) throw SceneError(name, 0, kUtf16Text);
    return parse_scene(text, name, threads);
}

}  // namespace rt
