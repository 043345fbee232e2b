// libFuzzer target: the hardware-profile parser (model/golden/profile.cpp parseProfile).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pst::fuzz::profile(std::string(reinterpret_cast<const char*>(data), size));
    return 0;
}
