// libFuzzer target: the scene-file parser (testbench/scene). Any input must either parse or be
// refused with an InputError; a crash, a sanitizer report or any other exception is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "input_error.h"
#include "scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        // A small image: the parser's checks, not the rasterizer's memory, are under test.
        pst::Scene s = pst::parseScene(text, "fuzz.toml", 8, 8);
        (void)s.layers();
    } catch (const pst::InputError&) {
    }
    return 0;
}
