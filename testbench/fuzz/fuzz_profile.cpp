// libFuzzer target: the hardware-profile parser (model/golden/profile.cpp parseProfile).
#include <cstddef>
#include <cstdint>
#include <string>

#include "input_error.h"
#include "profile.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        pst::Profile p = pst::parseProfile(text, "fuzz.toml");
        (void)p.clutSize();
    } catch (const pst::InputError&) {
    }
    return 0;
}
