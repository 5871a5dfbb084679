// Reading a scene file: what is not a scene file at all (missing, unreadable, a folder,
// too large, empty, UTF-16) is refused here, with no line; the text goes to parse_scene().
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include "raytracer/helper_pool.h"
#include "raytracer/parser.h"
#include "raytracer/scene_error.h"

namespace rt {

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
    return parse_scene(text, path, available_cores());
}

}  // namespace rt
