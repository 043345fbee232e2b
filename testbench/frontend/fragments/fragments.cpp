#include "fragments.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

#include "scene.h"  // InputError

namespace pst {

namespace {
const char* kFieldNames[9] = {"s", "t", "r", "ds/dx", "dt/dx", "dr/dx", "ds/dy", "dt/dy", "dr/dy"};

// A token for a message: control bytes (NUL among them) as \xNN.
std::string printable(const std::string& tok) {
    std::string out;
    char buf[8];
    for (unsigned char ch : tok) {
        if (ch < 0x20 || ch == 0x7f) {
            std::snprintf(buf, sizeof buf, "\\x%02x", ch);
            out += buf;
        } else {
            out += char(ch);
        }
    }
    return out;
}
}

std::vector<FragmentRecord> readFragments(std::istream& in, const std::string& path) {
    std::vector<FragmentRecord> out;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream ls(line);
        std::string tok;
        double v[9];
        int n = 0;
        auto where = [&](const std::string& field) {
            return path + ":" + std::to_string(lineNo) + ": " + field + ": ";
        };
        while (ls >> tok) {
            if (n == 9) throw InputError(where("line") + "more than 9 numbers");
            errno = 0;
            char* end = nullptr;
            double x = std::strtod(tok.c_str(), &end);
            // The whole token must be the number (a NUL byte inside it is not).
            if (end == tok.c_str() || end != tok.c_str() + tok.size())
                throw InputError(where(kFieldNames[n]) + "not a number: '" + printable(tok) + "'");
            // ERANGE on underflow (a subnormal or smaller) is a valid tiny number; on overflow not.
            if (!std::isfinite(x) || (errno == ERANGE && std::abs(x) >= 1.0))
                throw InputError(where(kFieldNames[n]) + "NaN, infinite or out-of-range number '" + tok + "'");
            if (std::abs(x) > kMaxSceneNumber)
                throw InputError(where(kFieldNames[n]) + "magnitude must be at most 1e6 (got '" + tok + "')");
            v[n++] = x;
        }
        if (n == 0) continue;
        if (n != 9)
            throw InputError(where("line") + "expected 9 numbers (s t r, ds/dx, ds/dy), got " + std::to_string(n));
        out.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}});
    }
    return out;
}

std::vector<FragmentRecord> loadFragments(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open file");
    return readFragments(in, path);
}

void writeFragments(std::ostream& out, const std::vector<FragmentRecord>& frags) {
    out << "# s t r  ds/dx dt/dx dr/dx  ds/dy dt/dy dr/dy\n";
    char buf[512];
    for (const auto& f : frags) {
        std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g  %.17g %.17g %.17g  %.17g %.17g %.17g\n",
                      f.s.x, f.s.y, f.s.z, f.dsdx.x, f.dsdx.y, f.dsdx.z, f.dsdy.x, f.dsdy.y, f.dsdy.z);
        out << buf;
    }
}

}  // namespace pst
