// libFuzzer target: the OBJ mesh reader (testbench/frontend/rasterizer/objmesh.h: readObjMesh, strict).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pst::fuzz::obj(std::string(reinterpret_cast<const char*>(data), size));
    return 0;
}
