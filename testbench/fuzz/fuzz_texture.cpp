// libFuzzer target: the texture-block parser (testbench/scene parseTexture, `pst eval --texture`).
#include <cstddef>
#include <cstdint>
#include <string>

#include "input_error.h"
#include "scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        pst::Texture t = pst::parseTexture(text, "fuzz.toml");
        (void)t.clut.size();
    } catch (const pst::InputError&) {
    }
    return 0;
}
