// libFuzzer harness over the whole pipeline: parse, then render what parses at no more
// than 8x8 pixels: the fuzzer looks for crashes and undefined behaviour in the tracer,
// not for big images. Writing the file is left out: it would be slow, and
// tests/bad_input.cpp covers it.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "raytracer/parser.h"
#include "raytracer/render.h"
#include "raytracer/scene_error.h"
#include "scene_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    rt::Scene scene;
    try {
        scene = rt::parse_scene(text, "fuzz.txt");
    } catch (const rt::SceneError& e) {
        fuzz::check_refusal(e.what(), "fuzz.txt");
        return 0;
    }
    fuzz::check_accepted(scene);
    scene.columns = std::min(scene.columns, 8);
    scene.rows = std::min(scene.rows, 8);
    const rt::Image image = rt::render<double>(scene);
    fuzz::require(image.width == scene.columns && image.height == scene.rows);
    fuzz::require(image.rgb.size() ==
                  static_cast<std::size_t>(scene.columns) * static_cast<std::size_t>(scene.rows) * 3);
    return 0;
}
