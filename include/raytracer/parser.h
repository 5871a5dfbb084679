// The scene-file reader: a hand-written, line-oriented parser that enforces every rule
// of SPEC section 2 and throws SceneError with the file and line of the first mistake.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

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

// Reads and parses a scene file, on as many threads as there are cores. Refuses what is not a scene file at
// all (missing, unreadable, a directory, empty, binary) with a SceneError that has no line.
Scene load_scene(const std::string& path);

}  // namespace rt
