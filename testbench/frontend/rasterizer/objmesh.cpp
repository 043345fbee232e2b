#include "objmesh.h"

#include <cmath>
#include <stdexcept>

#include <tiny_obj_loader.h>

namespace pst {

Mesh loadObjMesh(const std::string& path, double maxCoord, size_t maxTriangles) {
    tinyobj::ObjReaderConfig cfg;
    cfg.triangulate = true;
    cfg.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, cfg)) {
        std::string e = reader.Error();
        while (!e.empty() && (e.back() == '\n' || e.back() == ' ')) e.pop_back();
        throw std::runtime_error(e.empty() ? "cannot read the OBJ file" : e);
    }
    const tinyobj::attrib_t& at = reader.GetAttrib();
    Mesh m;
    const size_t nv = at.vertices.size() / 3;
    for (size_t i = 0; i < nv; ++i) {
        const glm::dvec3 p(at.vertices[3 * i], at.vertices[3 * i + 1], at.vertices[3 * i + 2]);
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(p[k]) || std::abs(p[k]) > maxCoord)
                throw std::runtime_error("vertex " + std::to_string(i + 1) + ": coordinate not finite or beyond " +
                                         std::to_string(maxCoord));
        m.positions.push_back(p);
    }
    m.texcoords = m.positions;
    for (const tinyobj::shape_t& sh : reader.GetShapes()) {
        size_t first = 0;
        for (size_t f = 0; f < sh.mesh.num_face_vertices.size(); ++f) {
            const size_t n = sh.mesh.num_face_vertices[f];
            if (n != 3) throw std::runtime_error("shape '" + sh.name + "': face " + std::to_string(f + 1) + " has " +
                                                 std::to_string(n) + " vertices after triangulation");
            std::array<uint32_t, 3> tri{};
            for (size_t k = 0; k < 3; ++k) {
                const int vi = sh.mesh.indices[first + k].vertex_index;
                if (vi < 0 || size_t(vi) >= nv)
                    throw std::runtime_error("shape '" + sh.name + "': face " + std::to_string(f + 1) +
                                             ": vertex index out of range (" + std::to_string(nv) + " vertices)");
                tri[k] = uint32_t(vi);
            }
            m.triangles.push_back(tri);
            if (m.triangles.size() > maxTriangles)
                throw std::runtime_error("more than " + std::to_string(maxTriangles) + " triangles");
            first += n;
        }
    }
    if (m.triangles.empty()) throw std::runtime_error("no faces");
    return m;
}

}  // namespace pst
