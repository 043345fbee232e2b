// Triangle meshes from Wavefront OBJ files, read strictly by a small line parser: positions
// only, polygons fanned into triangles; the solid texture coordinate of a vertex is its position,
// as for the built-in meshes (mesh.h).
//
// What is read (scenes/README.md, "OBJ meshes"):
//   v X Y Z [W]   a position: three finite decimal numbers, |X|, |Y|, |Z| <= maxCoord; W, when
//                 given, must be 1 (v X Y Z R G B, vertex colours, is read too, the colours
//                 checked and dropped)
//   vt U [V [W]], vn X Y Z   counted (so that face references to them can be checked), not kept
//   f A B C ...   a polygon of at least 3 corners, each V, V/T, V//N or V/T/N (all corners of one
//                 form); an index is a decimal integer, 1..count, or negative: -1 is the last
//                 one defined so far; an index must name an element defined above its line
//   o g s mg usemtl mtllib lod vp, and the display attributes (bevel c_interp d_interp
//                 shadow_obj trace_obj maplib usemap), comments (#) and blank lines: ignored
// Anything else is refused: unknown statements, lines and points (l, p), free-form geometry
// (curv, surf, cstype, ...), a line continuation (trailing backslash). A UTF-8 byte-order mark
// at the start is skipped; lines end in LF or CRLF.
//
// Every refusal is an InputError "FILE:LINE: KEYWORD: what" (or "FILE: what" for the file as a
// whole: not a regular file, cannot open, too large, no faces), FILE as given.
//
// Memory: the limits are checked while reading, before anything grows past them: at most
// limits.maxBytes bytes read (the input is streamed through a 64 KiB buffer, never held), lines
// of at most kMaxObjLine bytes, at most maxVertices positions and maxTriangles triangles. The
// heap in use while reading stays below
//     72 bytes x vertices + 36 bytes x triangles + 2 MiB
// (positions 24 bytes each and triangles 12, vectors doubling; the texcoords copy at the end;
// the line-sized scratch: the 64 KiB buffer, the line, its tokens and a face's corners, under
// 1.2 MiB with their growth), so at the default limits (2^22 vertices, kMaxSceneTriangles =
// 2^22 triangles) below 434 MiB
// whatever the input; a 1M-face mesh (0.5M vertices) adds 35 MiB at peak, an endless input
// 2 MiB (objmesh_test measures both).
//
// Zero-area triangles (a repeated corner, three collinear corners) are kept here: they are
// valid OBJ; render and atlas both skip them (mesh.h: zeroArea).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "mesh.h"

namespace pst {

constexpr uint64_t kMaxObjBytes = uint64_t(1) << 30;   // 1 GiB
constexpr size_t kMaxObjVertices = size_t(1) << 22;
constexpr size_t kMaxObjTriangles = size_t(1) << 22;   // = kMaxSceneTriangles
constexpr size_t kMaxObjLine = size_t(1) << 16;         // 64 KiB

struct ObjLimits {
    double maxCoord = 1e6;                  // |coordinate| bound (scene.h: kMaxSceneNumber)
    uint64_t maxBytes = kMaxObjBytes;
    size_t maxVertices = kMaxObjVertices;
    size_t maxTriangles = kMaxObjTriangles;
    std::string triangleLimit = "the OBJ limit";  // what maxTriangles is, for the message
};

// Reads the file at `path`: refuses anything but a regular file by kind before opening it
// (std::filesystem::status: a directory, a device such as /dev/zero, a FIFO), and a file larger
// than limits.maxBytes before reading it. Throws InputError (input_error.h).
Mesh loadObjMesh(const std::string& path, const ObjLimits& limits = ObjLimits());
Mesh loadObjMesh(const std::string& path, double maxCoord, size_t maxTriangles);

// Reads OBJ text from a stream; `name` is the FILE of messages. The same checks, limits
// included (the byte limit counts what is read, so an endless stream is refused at it).
Mesh readObjMesh(std::istream& in, const std::string& name, const ObjLimits& limits = ObjLimits());

}  // namespace pst
