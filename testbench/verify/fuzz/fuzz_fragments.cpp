// libFuzzer target: the fragment-file parser (testbench/frontend/fragments readFragments).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pst::fuzz::fragments(std::string(reinterpret_cast<const char*>(data), size));
    return 0;
}
