// The strict OBJ reader (objmesh.h): every class of malformed input refused with
// "FILE:LINE: KEYWORD: what", the forms it reads, its size limits checked while reading (peak
// memory of a 1M-face mesh and of an endless input measured in a child process), and files
// refused by kind before they are read.
#include "objmesh.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <streambuf>
#include <string>

#include <gtest/gtest.h>

#include "input_error.h"

namespace pst {
namespace {

namespace fs = std::filesystem;

const char* kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

Mesh read(const std::string& text, const ObjLimits& lim = ObjLimits()) {
    std::istringstream in(text);
    return readObjMesh(in, "m.obj", lim);
}

// The message of the refusal ("" when accepted; any exception but InputError fails).
std::string refusal(const std::string& text, const ObjLimits& lim = ObjLimits()) {
    try {
        read(text, lim);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

#define EXPECT_REFUSED(text, message) EXPECT_EQ(refusal(text), message) << "input: " << (text)

TEST(ObjMesh, ReadsTrianglesAndPolygons) {
    const Mesh m = read(std::string(kTri) + "v 1 1 0\nf 1 2 3\nf 1 2 4 3\n");
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[3], glm::dvec3(1, 1, 0));
    EXPECT_EQ(m.texcoords, m.positions);
    ASSERT_EQ(m.triangles.size(), 3u);  // the quad fanned from its first corner
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 1, 3}));
    EXPECT_EQ(m.triangles[2], (std::array<uint32_t, 3>{0, 3, 2}));
}

TEST(ObjMesh, RefusesCoordinatesThatAreNotFiniteNumbers) {
    EXPECT_REFUSED("v 0 one 1\n", "m.obj:1: v: y 'one' is not a number");
    EXPECT_REFUSED("# c\nv 0 1 nan\n", "m.obj:2: v: z 'nan' is not finite");
    EXPECT_REFUSED("v inf 1 0\n", "m.obj:1: v: x 'inf' is not finite");
    EXPECT_REFUSED("v 0 -Infinity 0\n", "m.obj:1: v: y '-Infinity' is not finite");
    EXPECT_REFUSED("v 0 1\n", "m.obj:1: v: expected x y z (or x y z w, x y z r g b), got 2 values");
    EXPECT_REFUSED("v\n", "m.obj:1: v: expected x y z (or x y z w, x y z r g b), got 0 values");
    EXPECT_REFUSED("v 0 1 2 3 4\n", "m.obj:1: v: expected x y z (or x y z w, x y z r g b), got 5 values");
    EXPECT_REFUSED("v 0 1.0abc 2\n", "m.obj:1: v: y '1.0abc' is not a number (trailing 'abc')");
    EXPECT_REFUSED("v 0 1,5 2\n", "m.obj:1: v: y '1,5' is not a number (trailing ',5')");
    EXPECT_REFUSED("v 0 0x10 2\n", "m.obj:1: v: y '0x10' is not a number (trailing 'x10')");
    EXPECT_REFUSED("v 0 +-1 2\n", "m.obj:1: v: y '+-1' is not a number");
    EXPECT_REFUSED("v 0 1e999 2\n", "m.obj:1: v: y '1e999' is out of range");
    EXPECT_REFUSED("v 2e6 0 0\n", "m.obj:1: v: x '2e6' is beyond +-1e+06");
    EXPECT_REFUSED("v 0 0 0 2\n", "m.obj:1: v: w '2' is not 1 (rational vertices are not supported)");
    EXPECT_REFUSED("v 0 0 0 1 0 nan\n", "m.obj:1: v: b 'nan' is not finite");
    EXPECT_REFUSED("vt 0 x\n", "m.obj:1: vt: v 'x' is not a number");
    EXPECT_REFUSED("vn 0 0\n", "m.obj:1: vn: expected x y z, got 2 values");
    EXPECT_REFUSED("vn 0 0 inf\n", "m.obj:1: vn: z 'inf' is not finite");
    // What is accepted: signs, exponents, a leading '+', w = 1, vertex colours.
    const Mesh m = read("v +1.5 -2e-1 .25 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(m.positions[0], glm::dvec3(1.5, -0.2, 0.25));
}

TEST(ObjMesh, RefusesMalformedIndices) {
    const std::string v(kTri);
    EXPECT_REFUSED(v + "f 1 2 4294967299\n", "m.obj:4: f: vertex index '4294967299' out of range (3 vertices defined above)");
    EXPECT_REFUSED(v + "f 1 2 99999999999999999999999\n",
                   "m.obj:4: f: vertex index '99999999999999999999999' out of range (3 vertices defined above)");
    EXPECT_REFUSED(v + "f 1 2 3abc\n", "m.obj:4: f: vertex index '3abc' is not an integer");
    EXPECT_REFUSED(v + "f 1 2 3.7\n", "m.obj:4: f: vertex index '3.7' is not an integer");
    EXPECT_REFUSED(v + "f 1 2 +3\n", "m.obj:4: f: vertex index '+3' is not an integer");
    EXPECT_REFUSED(v + "f 1 2 -\n", "m.obj:4: f: vertex index '-' is not an integer");
    EXPECT_REFUSED(v + "f 0 1 2\n", "m.obj:4: f: vertex index 0 (OBJ indices count from 1, or back from -1)");
    EXPECT_REFUSED(v + "f 1 2 4\n", "m.obj:4: f: vertex index '4' out of range (3 vertices defined above)");
    EXPECT_REFUSED(v + "f 1 2 -4\n", "m.obj:4: f: vertex index '-4' out of range (3 vertices defined above)");
    // A forward reference: vertex 4 is defined below the face.
    EXPECT_REFUSED(v + "f 1 2 4\nv 1 1 0\n", "m.obj:4: f: vertex index '4' out of range (3 vertices defined above)");
    EXPECT_REFUSED(v + "f 1/1 2/1 3/1\n", "m.obj:4: f: texture coordinate index '1' out of range (0 texture coordinates defined above)");
    EXPECT_REFUSED(v + "vn 0 0 1\nf 1//1 2//2 3//1\n", "m.obj:5: f: normal index '2' out of range (1 normal defined above)");
    EXPECT_REFUSED(v + "vt 0 0\nf 1/1 2/x 3/1\n", "m.obj:5: f: texture coordinate index 'x' is not an integer");
    EXPECT_REFUSED(v + "f 1/ 2/ 3/\n", "m.obj:4: f: missing texture coordinate index");
    EXPECT_REFUSED(v + "f /1 2 3\n", "m.obj:4: f: missing vertex index");
    EXPECT_REFUSED(v + "f 1/1/1/1 2 3\n", "m.obj:4: f: corner '1/1/1/1' has more than 3 parts (V, V/T, V//N or V/T/N)");
    EXPECT_REFUSED(v + "vt 0 0\nf 1 2/1 3\n",
                   "m.obj:5: f: corner '2/1' is not of the form of corner 1 '1' (V, V/T, V//N or V/T/N, the same for every corner)");
}

TEST(ObjMesh, NegativeIndicesCountBackFromTheLastDefined) {
    const Mesh m = read(std::string(kTri) + "f -3 -2 -1\nv 1 1 0\nf -3 -1 -2\n");
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{1, 3, 2}));
}

TEST(ObjMesh, ReadsTheCornerForms) {
    const std::string head = std::string(kTri) + "vt 0 0\nvt 1 0 0\nvt 0\nvn 0 0 1\n";
    for (const char* f : {"f 1/1/1 2/2/1 3/3/1\n", "f 1//1 2//1 3//1\n", "f 1/1 2/2 3/3\n", "f 1 2 3\n",
                          "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n"}) {
        const Mesh m = read(head + f);
        ASSERT_EQ(m.triangles.size(), 1u) << f;
        EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2})) << f;
    }
}

TEST(ObjMesh, RefusesFacesOfFewerThanThreeVertices) {
    EXPECT_REFUSED(std::string(kTri) + "f 1 2\n", "m.obj:4: f: a face needs at least 3 vertices, got 2");
    EXPECT_REFUSED(std::string(kTri) + "f 1 2 3\nf 1\n", "m.obj:5: f: a face needs at least 3 vertices, got 1");
    EXPECT_REFUSED(std::string(kTri) + "f\n", "m.obj:4: f: a face needs at least 3 vertices, got 0");
}

TEST(ObjMesh, ByteOrderMarkAndCrlf) {
    const std::string plain = std::string(kTri) + "v 1 1 0\nf 1 2 3\nf 2 4 3\n";
    const Mesh want = read(plain);
    // The first line is not hidden by a byte-order mark: indices keep their vertices.
    const Mesh bom = read("\xEF\xBB\xBF" + plain);
    EXPECT_EQ(bom.positions, want.positions);
    EXPECT_EQ(bom.triangles, want.triangles);
    std::string crlf;
    for (char c : plain) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    const Mesh w = read("\xEF\xBB\xBF" + crlf);
    EXPECT_EQ(w.positions, want.positions);
    EXPECT_EQ(w.triangles, want.triangles);
    // A last line without a newline is read.
    EXPECT_EQ(read(std::string(kTri) + "f 1 2 3").triangles.size(), 1u);
    // A mark anywhere else, a lone CR (old Mac line ends), a control character: refused.
    EXPECT_REFUSED(std::string(kTri) + "\xEF\xBB\xBF" + "f 1 2 3\n", "m.obj:4: unknown statement '\xEF\xBB\xBF" "f' "
                   "(expected v, vt, vn, f, o, g, s, usemtl, mtllib or #)");
    EXPECT_REFUSED("v 0 0 0\rv 1 0 0\r", "m.obj:1: a carriage return inside the line (lines end in LF or CRLF)");
    EXPECT_REFUSED(std::string("v 0 0 0\n") + '\0' + "\n", "m.obj:2: control character 0x00 (not a text file?)");
}

TEST(ObjMesh, RefusesWhatItDoesNotRead) {
    const std::string v(kTri);
    EXPECT_REFUSED(v, "m.obj: no faces");
    EXPECT_REFUSED("", "m.obj: no faces");
    EXPECT_REFUSED(v + "vertex 1 2 3\n", "m.obj:4: unknown statement 'vertex' (expected v, vt, vn, f, o, g, s, usemtl, mtllib or #)");
    EXPECT_REFUSED(v + "l 1 2\n", "m.obj:4: l: lines are not supported (only polygon faces, f)");
    EXPECT_REFUSED(v + "p 1\n", "m.obj:4: p: points are not supported (only polygon faces, f)");
    EXPECT_REFUSED(v + "cstype bezier\n", "m.obj:4: cstype: free-form geometry is not supported (only polygon faces, f)");
    EXPECT_REFUSED(v + "f 1 2 \\\n3\n", "m.obj:4: f: a line continuation (trailing backslash) is not supported");
    // Ignored statements and comments.
    EXPECT_EQ(read("# x\nmtllib a.mtl\no thing\ng a b\ns off\nusemtl m\n" + v + "  \n\tf 1 2 3 # end\n").triangles.size(),
              1u);
}

TEST(ObjMesh, LimitsCheckedWhileReading) {
    ObjLimits lim;
    lim.maxVertices = 3;
    EXPECT_EQ(refusal(std::string(kTri) + "f 1 2 3\nv 1 1 0\n", lim), "m.obj:5: v: more than 3 vertices (the OBJ limit)");
    lim = ObjLimits();
    lim.maxTriangles = 2;
    EXPECT_EQ(refusal(std::string(kTri) + "v 1 1 0\nf 1 2 3\nf 1 2 3 4\n", lim),
              "m.obj:6: f: more than 2 triangles (the OBJ limit)");
    lim.maxTriangles = 0;  // what a scene's budget leaves (scene.cpp)
    lim.triangleLimit = "what the scene's limit leaves";
    EXPECT_EQ(refusal(std::string(kTri) + "f 1 2 3\n", lim), "m.obj:4: f: more than 0 triangles (what the scene's limit leaves)");
    lim = ObjLimits();
    lim.maxBytes = 100;
    std::string comments;
    for (int i = 0; i < 10; ++i) comments += "# 0123456789\n";  // 13 bytes a line: byte 101 on line 10
    EXPECT_EQ(refusal(std::string(kTri) + "f 1 2 3\n" + comments, lim), "m.obj:10: more than 100 bytes (the OBJ size limit)");
    EXPECT_EQ(refusal("v 0 0 0 " + std::string(kMaxObjLine, ' ')), "m.obj:1: line longer than 64 KiB");
}

fs::path tempDir() {
    fs::path d = fs::temp_directory_path() / ("objmesh_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

std::string loadRefusal(const std::string& path, const ObjLimits& lim = ObjLimits()) {
    try {
        loadObjMesh(path, lim);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ObjMesh, RefusesFilesByKindBeforeReading) {
    const fs::path d = tempDir();
    EXPECT_EQ(loadRefusal(d.string()), d.string() + ": not a regular file (a directory)");
    EXPECT_EQ(loadRefusal("/dev/zero"), "/dev/zero: not a regular file (a character device)");
    EXPECT_EQ(loadRefusal("/dev/null"), "/dev/null: not a regular file (a character device)");
    const fs::path fifo = d / "fifo.obj";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);  // opening it would block: refused unopened
    EXPECT_EQ(loadRefusal(fifo.string()), fifo.string() + ": not a regular file (a FIFO)");
    EXPECT_EQ(loadRefusal((d / "absent.obj").string()), (d / "absent.obj").string() + ": cannot open (No such file or directory)");
    // A regular file over the byte limit is refused from its size, before reading.
    const fs::path big = d / "big.obj";
    std::ofstream(big) << kTri << "f 1 2 3\n";
    ObjLimits lim;
    lim.maxBytes = 16;
    EXPECT_EQ(loadRefusal(big.string(), lim), big.string() + ": 32 bytes, more than 16 bytes (the OBJ size limit)");
    // And read through a symbolic link.
    fs::create_symlink(big, d / "link.obj");
    EXPECT_EQ(loadObjMesh((d / "link.obj").string()).triangles.size(), 1u);
    // The line a message names is the file's line.
    std::ofstream(d / "bad.obj") << kTri << "\n\nf 1 2 x\n";
    EXPECT_EQ(loadRefusal((d / "bad.obj").string()), (d / "bad.obj").string() + ":6: f: vertex index 'x' is not an integer");
    fs::remove_all(d);
}

// Zero-area triangles are valid OBJ and kept; render and atlas skip them (mesh.h: zeroArea).
TEST(ObjMesh, KeepsZeroAreaTrianglesForTheSharedRule) {
    const Mesh m = read("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\nf 1 1 2\n");
    ASSERT_EQ(m.triangles.size(), 3u);
    EXPECT_EQ(zeroAreaTriangles(m), 2u);
}

// ---- Peak memory ---------------------------------------------------------------------------

long statusKiB(const char* key) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + std::strlen(key));
    return -1;
}

struct Measured {
    long peakKiB = -1;    // VmHWM - VmRSS before: the resident memory the call added at its peak
    std::string result;   // the refusal, or "ok N" (triangles)
    double seconds = 0;
};

// Runs `load` in a child process (its own high-water mark) and reports what it added at peak.
Measured inChild(const std::function<Mesh()>& load) {
    int fd[2];
    if (::pipe(fd) != 0) return {};
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fd[0]);
        const long before = statusKiB("VmRSS:");
        std::string r;
        const auto t0 = std::chrono::steady_clock::now();
        try {
            r = "ok " + std::to_string(load().triangles.size());
        } catch (const std::exception& e) {
            r = e.what();
        }
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const std::string msg = std::to_string(statusKiB("VmHWM:") - before) + " " + std::to_string(s) + " " + r;
        (void)!::write(fd[1], msg.data(), msg.size());
        ::_exit(0);
    }
    ::close(fd[1]);
    std::string msg;
    char buf[4096];
    for (ssize_t n; (n = ::read(fd[0], buf, sizeof buf)) > 0;) msg.append(buf, size_t(n));
    ::close(fd[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    Measured m;
    std::istringstream in(msg);
    in >> m.peakKiB >> m.seconds;
    std::getline(in >> std::ws, m.result);
    return m;
}

// A generated 1M-face mesh (a 708 x 708 quad grid, 1,002,528 triangles) reads within the stated
// bound, 72 bytes a vertex + 36 a triangle + 2 MiB.
TEST(ObjMesh, MillionFaceMeshReadsWithinTheBound) {
    const fs::path d = tempDir();
    const fs::path file = d / "grid.obj";
    constexpr int N = 708;
    {
        std::ofstream out(file);
        for (int j = 0; j <= N; ++j)
            for (int i = 0; i <= N; ++i) out << "v " << i << " " << j << " 0\n";
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < N; ++i) {
                const int a = j * (N + 1) + i + 1;
                out << "f " << a << " " << a + 1 << " " << a + N + 2 << " " << a + N + 1 << "\n";
            }
    }
    const long V = long(N + 1) * (N + 1), T = 2L * N * N;
    const Measured m = inChild([&] { return loadObjMesh(file.string()); });
    const long boundKiB = (72 * V + 36 * T) / 1024 + 2048;
    std::printf("1M-face mesh (%ld vertices, %ld triangles, %.1f MiB file): peak +%ld KiB (bound %ld KiB), %.2f s\n", V, T,
                double(fs::file_size(file)) / (1 << 20), m.peakKiB, boundKiB, m.seconds);
    EXPECT_EQ(m.result, "ok " + std::to_string(T));
    EXPECT_GT(m.peakKiB, 0);
    EXPECT_LT(m.peakKiB, boundKiB);
    fs::remove_all(d);
}

// An endless stream of comment lines is refused at the byte limit (1 GiB) in constant memory;
// endless vertices at the vertex limit, within the bound.
class Endless : public std::streambuf {
public:
    explicit Endless(std::string line) : line_(std::move(line)) {
        for (int i = 0; i < 4096; ++i) buf_ += line_;
        setg(buf_.data(), buf_.data(), buf_.data() + buf_.size());
    }

protected:
    int_type underflow() override {
        setg(buf_.data(), buf_.data(), buf_.data() + buf_.size());
        return traits_type::to_int_type(buf_[0]);
    }

private:
    std::string line_, buf_;
};

TEST(ObjMesh, EndlessInputRefusedAtTheLimits) {
    const Measured c = inChild([] {
        Endless sb("# an endless comment, 64 bytes a line" + std::string(26, '.') + "\n");
        std::istream in(&sb);
        return readObjMesh(in, "endless.obj");
    });
    std::printf("endless comments: %s; peak +%ld KiB, %.2f s\n", c.result.c_str(), c.peakKiB, c.seconds);
    EXPECT_EQ(c.result, "endless.obj:16777217: more than 1 GiB (the OBJ size limit)");
    EXPECT_LT(c.peakKiB, 4096);
    const Measured v = inChild([] {
        Endless sb("v 1 2 3\n");
        std::istream in(&sb);
        return readObjMesh(in, "endless.obj");
    });
    const long boundKiB = 72L * long(kMaxObjVertices) / 1024 + 2048;
    std::printf("endless vertices: %s; peak +%ld KiB (bound %ld KiB), %.2f s\n", v.result.c_str(), v.peakKiB, boundKiB,
                v.seconds);
    EXPECT_EQ(v.result, "endless.obj:4194305: v: more than 4194304 vertices (the OBJ limit)");
    EXPECT_LT(v.peakKiB, boundKiB);
}

}  // namespace
}  // namespace pst
