// libFuzzer target: the scene-file parser (testbench/frontend/scene checkScene: parseScene's checks, no meshes or tables).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pst::fuzz::scene(std::string(reinterpret_cast<const char*>(data), size));
    return 0;
}
