// libFuzzer harness over the parser: any bytes either parse into a scene that keeps
// every rule of SPEC section 2, or are refused with a one-line SceneError; nothing
// else (no crash, no other exception, no undefined behaviour under the sanitizers).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "raytracer/parser.h"
#include "raytracer/scene_error.h"
#include "scene_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        fuzz::check_accepted(rt::parse_scene(text, "fuzz.txt"));
    } catch (const rt::SceneError& e) {
        fuzz::check_refusal(e.what(), "fuzz.txt");
    }
    return 0;
}
