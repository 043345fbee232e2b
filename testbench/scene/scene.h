// Scene files (TOML, parsed by toml++): camera, image, textures with colour maps, objects.
// The format is documented in scenes/README.md; every error names file, line and field.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "input_error.h"
#include "mesh.h"
#include "rasterizer.h"
#include "texture.h"

namespace toml {
inline namespace v3 {
class table;
}
}  // namespace toml

namespace pst {

struct SceneObject {
    std::string name;   // mesh kind and index, for messages
    Mesh mesh;          // world space, texcoords already mapped to texture space
    int texture = 0;    // index into Scene::textures
    int layer = 0;      // 0 = opaque z-buffered pass; k > 0 = pass k blended "over" layer < k
};

struct Scene {
    std::string path;
    std::string title;
    Camera camera;
    glm::dvec4 background{0.0, 0.0, 0.0, 1.0};
    std::vector<Texture> textures;
    std::vector<SceneObject> objects;
    int layers() const;  // 1 + the highest layer used
};

// Reads a scene file. `width`/`height` > 0 override the file's image size.
Scene loadScene(const std::string& path, int width = 0, int height = 0);
Scene parseScene(const std::string& text, const std::string& path, int width = 0, int height = 0);

// Reads a texture block: the same keys as a [textures.NAME] table of a scene file, at the
// top level of its own file (used by `pst eval`).
Texture loadTexture(const std::string& path);
Texture parseTexture(const std::string& text, const std::string& path);

}  // namespace pst
