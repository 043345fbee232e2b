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

// Bounds on what a scene file (or a size flag) may ask for: every number's magnitude, the
// image (memory grows about 140 bytes a pixel) and the meshes' triangles (about 40 bytes each).
constexpr double kMaxSceneNumber = 1e6;
constexpr int kMaxImageSide = 16384;
constexpr long long kMaxImagePixels = 4096LL * 4096;
constexpr size_t kMaxSceneTriangles = size_t(1) << 22;

struct SceneObject {
    std::string name;   // mesh kind and index, for messages
    // Where the mesh comes from, a message's prefix: "FILE:LINE: objects[K].mesh: 'KIND'" (the
    // scene file's mesh key) or "FILE:LINE: objects[K].file: PATH" (an OBJ mesh, its file).
    std::string meshSource;
    Mesh mesh;          // world space, texcoords already mapped to texture space
    int texture = 0;    // index into Scene::textures
    int layer = 0;      // 0 = opaque z-buffered pass; k > 0 = pass k blended "over" layer < k
};

// The optional time track ([animation] in a scene file, scenes/README.md): each track keys one
// field of the file (a path such as "camera.eye" or "textures.fire.octaves[*].offset") over the
// sequence time t in [0, 1], interpolated linearly; before the first key and after the last the
// end keys hold.
struct TrackKey {
    double t = 0;
    std::vector<double> value;   // 1 number, or the 2..4 numbers of an array field
};
struct Track {
    std::string field;           // the path of the field it sets
    std::string where;           // "FILE:LINE" of the track, for messages
    std::vector<TrackKey> keys;  // t non-decreasing
    std::vector<double> at(double t) const;
};
struct Animation {
    int frames = 0;              // default frame count of `pst animate` (0: none given)
    double fps = 24;
    std::vector<Track> tracks;
    bool empty() const { return tracks.empty(); }
};

struct Scene {
    std::string path;
    std::string title;
    Camera camera;
    glm::dvec4 background{0.0, 0.0, 0.0, 1.0};
    std::vector<Texture> textures;
    std::vector<SceneObject> objects;
    Animation animation;         // empty for a still
    int layers() const;  // 1 + the highest layer used
};

// Reads a scene file. `width`/`height` > 0 override the file's image size.
Scene loadScene(const std::string& path, int width = 0, int height = 0);
Scene parseScene(const std::string& text, const std::string& path, int width = 0, int height = 0);

// Every check of parseScene (keys, values, bounds, every animation key) without building the
// meshes or the colour tables (what a parse costs): throws the same InputError for a bad file,
// except the meshes' triangle bound, which needs the meshes. For fuzzing (testbench/verify/fuzz).
void checkScene(const std::string& text, const std::string& path);

// The scene at sequence time t in [0, 1]: the file with every track's value at t in place of the
// field it keys (a file without tracks gives the still). loadScene/parseScene already checked
// every track at each of its keys, so these fail only between keys (e.g. eye == target).
Scene loadSceneAt(const std::string& path, double t, int width = 0, int height = 0);
Scene parseSceneAt(const std::string& text, const std::string& path, double t, int width = 0, int height = 0);

// Reads a texture block: the same keys as a [textures.NAME] table of a scene file, at the
// top level of its own file (used by `pst eval`).
Texture loadTexture(const std::string& path);
// parseTexture's checks without building the colour tables.
void checkTexture(const std::string& text, const std::string& path);
Texture parseTexture(const std::string& text, const std::string& path);

}  // namespace pst
