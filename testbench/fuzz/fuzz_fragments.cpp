// libFuzzer target: the fragment-file parser (testbench/fragments readFragments).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fragments.h"
#include "input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    try {
        const auto frags = pst::readFragments(in, "fuzz.frag");
        (void)frags.size();
    } catch (const pst::InputError&) {
    }
    return 0;
}
