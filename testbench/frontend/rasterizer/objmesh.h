// Triangle meshes from Wavefront OBJ files (Debian's tinyobjloader): positions only, polygons
// triangulated; the solid texture coordinate of a vertex is its position, as for the built-in
// meshes (mesh.h).
#pragma once

#include <string>

#include "mesh.h"

namespace pst {

// Throws std::runtime_error with what is wrong (cannot open, a parse error with the file's
// line when tinyobjloader gives one, no faces, a vertex index out of range, a non-finite or
// too large coordinate (|x| > maxCoord), more than maxTriangles triangles).
Mesh loadObjMesh(const std::string& path, double maxCoord, size_t maxTriangles);

}  // namespace pst
