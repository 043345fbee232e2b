#include "provenance.h"

#include <OpenImageIO/oiioversion.h>

namespace pst {
namespace {
std::vector<std::string>& args() {
    static std::vector<std::string> a;
    return a;
}
}  // namespace

void setCommandLine(int argc, char** argv) { args().assign(argv, argv + argc); }
const std::vector<std::string>& commandLine() { return args(); }

nlohmann::json provenance() {
    const BuildInfo& b = buildInfo();
    return {{"schema", kOutputSchema},
            {"commit", b.commit},
            {"tool_versions", {{"pst", b.version}, {"verilator", b.verilator}, {"compiler", b.compiler},
                               {"openimageio", OIIO_VERSION_STRING}}},
            {"command_line", commandLine()}};
}

nlohmann::json withProvenance(nlohmann::json doc) {
    const nlohmann::json p = provenance();   // kept alive: items() refers into it
    for (const auto& [k, v] : p.items()) doc[k] = v;
    return doc;
}

std::vector<std::pair<std::string, std::string>> junitProperties() {
    const nlohmann::json p = provenance();
    std::vector<std::pair<std::string, std::string>> out = {{"schema", std::to_string(kOutputSchema)},
                                                            {"commit", p["commit"].get<std::string>()}};
    for (auto& [k, v] : p["tool_versions"].items()) out.push_back({"tool_versions." + k, v.get<std::string>()});
    std::string line;
    for (const auto& a : commandLine()) line += (line.empty() ? "" : " ") + a;
    out.push_back({"command_line", line});
    return out;
}

}  // namespace pst
