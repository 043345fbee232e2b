// sourceDir() (source_dir.h): resolved at run time, nothing absolute compiled in. The build's
// configuration writes <build>/pst_source_dir, the source tree's path relative to the build
// tree (CMakeLists.txt); an executable of that build finds it by walking up from its own
// directory (/proc/self/exe), so the build tree and its checkout can move together.
#include "source_dir.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace pst {
namespace {

namespace fs = std::filesystem;

std::string fromExecutable() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return "";
    for (fs::path dir = exe.parent_path(); !dir.empty(); dir = dir.parent_path()) {
        std::ifstream in(dir / "pst_source_dir");
        std::string rel;
        if (in && std::getline(in, rel) && !rel.empty()) {
            const fs::path p = fs::path(rel).is_absolute() ? fs::path(rel) : dir / rel;
            std::string s = p.lexically_normal().string();
            while (s.size() > 1 && s.back() == '/') s.pop_back();
            return s;
        }
        if (dir == dir.root_path()) break;
    }
    return "";
}

}  // namespace

std::string sourceDir() {
    if (const char* env = std::getenv("PST_SOURCE_DIR")) return env;
    static const std::string found = [] {
        std::string s = fromExecutable();
        return s.empty() ? std::string(".") : s;
    }();
    return found;
}

}  // namespace pst
