// The project's source tree, for the tests and the CLI that read scenes, profiles, test data
// and scripts from it: $PST_SOURCE_DIR when set (ctest sets it), else the path CMake compiled
// in as PST_SOURCE_DIR_DEFAULT, else the working directory.
#pragma once

#include <cstdlib>
#include <string>

namespace pst {

inline std::string sourceDir() {
    if (const char* env = std::getenv("PST_SOURCE_DIR")) return env;
#ifdef PST_SOURCE_DIR_DEFAULT
    return PST_SOURCE_DIR_DEFAULT;
#else
    return ".";
#endif
}

}  // namespace pst
