// The project's source tree, for the tests and the CLI that read scenes, profiles, test data
// and scripts from it: $PST_SOURCE_DIR when set (ctest sets it), else the tree the running
// executable's build belongs to (source_dir.cpp: no path is compiled in), else the working
// directory.
#pragma once

#include <string>

namespace pst {

std::string sourceDir();

}  // namespace pst
