// Provenance of every JSON, JUnit and HTML output: which build wrote it and how it was asked.
// One helper for every writer: provenance() is merged into each JSON document's top level
// ("schema", "commit", "tool_versions", "command_line"), junitProperties() is the JUnit
// <properties> of the same values.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace pst {

// The version of the JSON outputs' layout (regress.json: an object with "runs" since 2).
constexpr int kOutputSchema = 2;

// Build facts, captured when the build ran (testbench/tool/reports/version.cmake).
struct BuildInfo {
    std::string version;     // the project's (CMake project VERSION)
    std::string commit;      // git commit, "-dirty" when tracked files differed from it
    std::string verilator;   // `verilator --version`
    std::string compiler;    // the C++ compiler's id and version
};
const BuildInfo& buildInfo();

// The command line of this run (main sets it; empty otherwise).
void setCommandLine(int argc, char** argv);
const std::vector<std::string>& commandLine();

// {"schema", "commit", "tool_versions": {pst, verilator, compiler, openimageio}, "command_line"}
nlohmann::json provenance();
// `doc` (an object) with provenance()'s keys added at its top level.
nlohmann::json withProvenance(nlohmann::json doc);
// The same as JUnit <property> name/value pairs.
std::vector<std::pair<std::string, std::string>> junitProperties();

}  // namespace pst
