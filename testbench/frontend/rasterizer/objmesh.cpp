#include "objmesh.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <string_view>
#include <system_error>
#include <vector>

#include "input_error.h"

namespace pst {

namespace {

namespace fs = std::filesystem;

// "1 GiB", "64 KiB", "1000 bytes": a limit printed short.
std::string bytesShort(uint64_t n) {
    const char* unit[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (u < 4 && n >= 1024 && n % 1024 == 0) n /= 1024, ++u;
    return std::to_string(n) + " " + unit[u];
}

std::string quoted(std::string_view s) {
    constexpr size_t kShow = 40;
    std::string out = "'";
    out += s.size() > kShow ? std::string(s.substr(0, kShow)) + "..." : std::string(s);
    return out + "'";
}

bool isSpace(char c) { return c == ' ' || c == '\t'; }

// Whitespace-separated tokens of one line (no CR, no control characters left).
const std::vector<std::string_view>& tokens(std::string_view line, std::vector<std::string_view>& out) {
    out.clear();
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isSpace(line[i])) ++i;
        const size_t b = i;
        while (i < line.size() && !isSpace(line[i])) ++i;
        if (i > b) out.push_back(line.substr(b, i - b));
    }
    return out;
}

class Reader {
public:
    Reader(const std::string& name, const ObjLimits& lim) : name_(name), lim_(lim) {}

    Mesh read(std::istream& in) {
        std::vector<char> buf(size_t(64) << 10);
        line_.reserve(256);
        bool first = true;
        for (;;) {
            const uint64_t room = lim_.maxBytes + 1 - bytes_;  // read at most one byte past the limit
            in.read(buf.data(), std::streamsize(std::min<uint64_t>(buf.size(), room)));
            const size_t got = size_t(in.gcount());
            if (got == 0) break;
            bytes_ += got;
            // The bytes up to the limit are read; the line holding the first byte past it is refused.
            const size_t use = bytes_ > lim_.maxBytes ? got - size_t(bytes_ - lim_.maxBytes) : got;
            size_t i = 0;
            if (first) {
                first = false;
                // A UTF-8 byte-order mark (a first chunk always holds its 3 bytes unless the
                // input is shorter).
                if (use >= 3 && std::memcmp(buf.data(), "\xEF\xBB\xBF", 3) == 0) i = 3;
            }
            while (i < use) {
                const char* nl = static_cast<const char*>(std::memchr(buf.data() + i, '\n', use - i));
                const size_t end = nl ? size_t(nl - buf.data()) : use;
                if (line_.size() + (end - i) > kMaxObjLine) fail("", "line longer than " + bytesShort(kMaxObjLine));
                line_.append(buf.data() + i, end - i);
                i = end;
                if (nl) {
                    endLine();
                    ++i;
                }
            }
            if (bytes_ > lim_.maxBytes) fail("", "more than " + bytesShort(lim_.maxBytes) + " (the OBJ size limit)");
            if (!in) break;
        }
        if (in.bad()) throw InputError(name_ + ": read error");
        if (!line_.empty()) endLine();
        if (mesh_.triangles.empty()) throw InputError(name_ + ": no faces");
        mesh_.texcoords = mesh_.positions;
        return std::move(mesh_);
    }

private:
    // "FILE:LINE: KEYWORD: what" ("FILE:LINE: what" for an empty keyword).
    [[noreturn]] void fail(const std::string& keyword, const std::string& what) const {
        if (keyword.empty()) throw InputError(inputWhere(name_, long(lineNo_ + 1)) + ": " + what);
        throw inputError(name_, long(lineNo_ + 1), keyword, what);
    }

    void endLine() {
        std::string_view l(line_);
        if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
        for (char c : l) {
            const unsigned char u = static_cast<unsigned char>(c);
            if (c == '\r') fail("", "a carriage return inside the line (lines end in LF or CRLF)");
            if ((u < 0x20 && c != '\t') || u == 0x7f) {
                char hex[8];
                std::snprintf(hex, sizeof hex, "0x%02x", u);
                fail("", std::string("control character ") + hex + " (not a text file?)");
            }
        }
        // A comment: from a '#' at the start of a line or after a blank to the end.
        for (size_t k = 0; k < l.size(); ++k)
            if (l[k] == '#' && (k == 0 || isSpace(l[k - 1]))) {
                l = l.substr(0, k);
                break;
            }
        parseLine(l);
        line_.clear();
        ++lineNo_;
    }

    double number(std::string_view tok, const std::string& kw, const char* what) const {
        std::string_view t = tok;
        if (!t.empty() && t[0] == '+') t.remove_prefix(1);
        double v = 0;
        const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
        if (r.ec == std::errc::invalid_argument || t.empty() || t[0] == '+' || (t.size() != tok.size() && t[0] == '-'))
            fail(kw, std::string(what) + " " + quoted(tok) + " is not a number");
        if (r.ptr != t.data() + t.size())
            fail(kw, std::string(what) + " " + quoted(tok) + " is not a number (trailing " +
                         quoted(std::string_view(r.ptr, size_t(t.data() + t.size() - r.ptr))) + ")");
        if (r.ec == std::errc::result_out_of_range) fail(kw, std::string(what) + " " + quoted(tok) + " is out of range");
        if (!std::isfinite(v)) fail(kw, std::string(what) + " " + quoted(tok) + " is not finite");
        return v;
    }

    // A 1-based or negative (relative) OBJ index of one of `count` elements defined so far -> 0-based.
    uint32_t index(std::string_view tok, uint64_t count, const std::string& kw, const char* kind, const char* kinds) const {
        if (tok.empty()) fail(kw, std::string("missing ") + kind + " index");
        std::string_view d = tok;
        const bool neg = d[0] == '-';
        if (neg) d.remove_prefix(1);
        if (d.empty()) fail(kw, std::string(kind) + " index " + quoted(tok) + " is not an integer");
        uint64_t v = 0;
        bool over = false;
        for (char c : d) {
            if (c < '0' || c > '9') fail(kw, std::string(kind) + " index " + quoted(tok) + " is not an integer");
            if (!over) {
                v = v * 10 + uint64_t(c - '0');
                if (v > 0xFFFFFFFFull) over = true;
            }
        }
        if (!over && v == 0) fail(kw, std::string(kind) + " index 0 (OBJ indices count from 1, or back from -1)");
        if (over || v > count)
            fail(kw, std::string(kind) + " index " + quoted(tok) + " out of range (" + std::to_string(count) + " " +
                         (count == 1 ? kind : kinds) + " defined above)");
        return uint32_t(neg ? count - v : v - 1);
    }

    void parseLine(std::string_view l) {
        const std::vector<std::string_view>& t = tokens(l, tok_);
        if (t.empty()) return;
        const std::string kw(t[0].substr(0, 16));
        if (t.back().back() == '\\') fail(kw, "a line continuation (trailing backslash) is not supported");
        const size_t n = t.size() - 1;
        if (kw == "v") {
            if (n != 3 && n != 4 && n != 6)
                fail(kw, "expected x y z (or x y z w, x y z r g b), got " + std::to_string(n) + " value" +
                             (n == 1 ? "" : "s"));
            static const char* names[] = {"x", "y", "z", "w", "r", "g"};
            glm::dvec3 p;
            for (size_t k = 0; k < n; ++k) {
                const double x = number(t[k + 1], kw, n == 6 && k >= 3 ? (k == 3 ? "r" : k == 4 ? "g" : "b") : names[k]);
                if (k < 3) {
                    if (std::abs(x) > lim_.maxCoord)
                        fail(kw, std::string(names[k]) + " " + quoted(t[k + 1]) + " is beyond +-" + shortNumber(lim_.maxCoord));
                    p[int(k)] = x;
                } else if (n == 4 && x != 1.0) {
                    fail(kw, "w " + quoted(t[k + 1]) + " is not 1 (rational vertices are not supported)");
                }
            }
            if (mesh_.positions.size() >= lim_.maxVertices)
                fail(kw, "more than " + std::to_string(lim_.maxVertices) + " vertices (the OBJ limit)");
            mesh_.positions.push_back(p);
        } else if (kw == "vt") {
            if (n < 1 || n > 3) fail(kw, "expected u [v [w]], got " + std::to_string(n) + " values");
            for (size_t k = 0; k < n; ++k) number(t[k + 1], kw, k == 0 ? "u" : k == 1 ? "v" : "w");
            ++texcoords_;
        } else if (kw == "vn") {
            if (n != 3) fail(kw, "expected x y z, got " + std::to_string(n) + " value" + (n == 1 ? "" : "s"));
            for (size_t k = 0; k < n; ++k) number(t[k + 1], kw, k == 0 ? "x" : k == 1 ? "y" : "z");
            ++normals_;
        } else if (kw == "f") {
            if (n < 3) fail(kw, "a face needs at least 3 vertices, got " + std::to_string(n));
            face_.clear();
            int form = -1;  // 0: V, 1: V/T, 2: V//N, 3: V/T/N
            for (size_t k = 1; k <= n; ++k) {
                std::string_view ref = t[k];
                std::string_view part[3];
                int parts = 0;
                for (;;) {
                    const size_t s = ref.find('/');
                    if (parts == 3) fail(kw, "corner " + quoted(t[k]) + " has more than 3 parts (V, V/T, V//N or V/T/N)");
                    part[parts++] = ref.substr(0, s);
                    if (s == std::string_view::npos) break;
                    ref.remove_prefix(s + 1);
                }
                const int f = parts == 1 ? 0 : parts == 2 ? 1 : part[1].empty() ? 2 : 3;
                if (form < 0) form = f;
                if (f != form)
                    fail(kw, "corner " + quoted(t[k]) + " is not of the form of corner 1 " + quoted(t[1]) +
                                 " (V, V/T, V//N or V/T/N, the same for every corner)");
                face_.push_back(index(part[0], mesh_.positions.size(), kw, "vertex", "vertices"));
                if (f == 1 || f == 3) index(part[1], texcoords_, kw, "texture coordinate", "texture coordinates");
                if (f >= 2) index(part[2], normals_, kw, "normal", "normals");
            }
            for (size_t k = 1; k + 1 < face_.size(); ++k) {
                if (mesh_.triangles.size() >= lim_.maxTriangles)
                    fail(kw, "more than " + std::to_string(lim_.maxTriangles) + " triangles (" + lim_.triangleLimit + ")");
                mesh_.triangles.push_back({face_[0], face_[k], face_[k + 1]});
            }
        } else if (kw == "o" || kw == "g" || kw == "s" || kw == "mg" || kw == "usemtl" || kw == "mtllib" ||
                   kw == "lod" || kw == "vp" || kw == "bevel" || kw == "c_interp" || kw == "d_interp" ||
                   kw == "shadow_obj" || kw == "trace_obj" || kw == "maplib" || kw == "usemap") {
            // Groups, materials, display attributes: nothing for a solid texture.
        } else if (kw == "l" || kw == "p") {
            fail(kw, std::string(kw == "l" ? "lines" : "points") + " are not supported (only polygon faces, f)");
        } else if (kw == "curv" || kw == "curv2" || kw == "surf" || kw == "cstype" || kw == "deg" || kw == "bmat" ||
                   kw == "step" || kw == "parm" || kw == "trim" || kw == "hole" || kw == "scrv" || kw == "sp" ||
                   kw == "end" || kw == "con") {
            fail(kw, "free-form geometry is not supported (only polygon faces, f)");
        } else {
            fail("", "unknown statement " + quoted(t[0]) + " (expected v, vt, vn, f, o, g, s, usemtl, mtllib or #)");
        }
    }

    static std::string shortNumber(double x) {
        char s[32];
        std::snprintf(s, sizeof s, "%g", x);
        return s;
    }

    const std::string& name_;
    const ObjLimits& lim_;
    Mesh mesh_;
    std::string line_;
    std::vector<std::string_view> tok_;
    std::vector<uint32_t> face_;
    uint64_t bytes_ = 0, lineNo_ = 0, texcoords_ = 0, normals_ = 0;
};

std::string kindOf(const fs::file_status& st) {
    switch (st.type()) {
        case fs::file_type::directory: return "a directory";
        case fs::file_type::block: return "a block device";
        case fs::file_type::character: return "a character device";
        case fs::file_type::fifo: return "a FIFO";
        case fs::file_type::socket: return "a socket";
        default: return "not a file";
    }
}

}  // namespace

Mesh readObjMesh(std::istream& in, const std::string& name, const ObjLimits& limits) {
    return Reader(name, limits).read(in);
}

Mesh loadObjMesh(const std::string& path, const ObjLimits& limits) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);  // follows symbolic links
    if (ec) throw InputError(path + ": cannot open (" + ec.message() + ")");
    if (!fs::is_regular_file(st)) throw InputError(path + ": not a regular file (" + kindOf(st) + ")");
    const uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > limits.maxBytes)
        throw InputError(path + ": " + std::to_string(size) + " bytes, more than " + bytesShort(limits.maxBytes) +
                         " (the OBJ size limit)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
    return readObjMesh(in, path, limits);
}

Mesh loadObjMesh(const std::string& path, double maxCoord, size_t maxTriangles) {
    ObjLimits lim;
    lim.maxCoord = maxCoord;
    lim.maxTriangles = maxTriangles;
    return loadObjMesh(path, lim);
}

}  // namespace pst
