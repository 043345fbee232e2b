// libFuzzer target: the texture-block parser (testbench/frontend/scene checkTexture, `pst eval --texture`).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pst::fuzz::texture(std::string(reinterpret_cast<const char*>(data), size));
    return 0;
}
