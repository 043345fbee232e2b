// Scene and texture files: TOML parsed by toml++, checked field by field.
#include "scene.h"
#include "subband.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <toml++/toml.h>

#include "objmesh.h"

#include "scene_parse.h"

namespace pst {
namespace {

using namespace scene_detail;

// --- Objects: a mesh, its placement, its texture space ------------------------------------
glm::dmat4 placement(const Ctx& c, const toml::table& t, const std::string& path,
                     const char* scaleKey, const char* rotateKey, const char* translateKey) {
    glm::dvec3 sc = getScale(c, t, path, scaleKey);
    if (sc.x == 0.0 || sc.y == 0.0 || sc.z == 0.0)
        c.fail(find(t, scaleKey), join(path, scaleKey), "must be non-zero (a zero scale flattens the object)");
    glm::dvec3 rot = getVec3(c, t, path, rotateKey, glm::dvec3(0.0));
    glm::dvec3 tr = getVec3(c, t, path, translateKey, glm::dvec3(0.0));
    // Applied in the order scale, rotate about x, then y, then z, translate.
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), tr);
    m = glm::rotate(m, glm::radians(rot.z), glm::dvec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(rot.y), glm::dvec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(rot.x), glm::dvec3(1, 0, 0));
    return glm::scale(m, sc);
}

SceneObject parseObject(const Ctx& c, const toml::table& t, const std::string& path,
                        const std::map<std::string, int>& textureIndex) {
    checkKeys(c, t, path, {"mesh", "texture", "layer", "subdiv", "slices", "stacks", "major_radius",
                           "minor_radius", "segments", "half_size", "divisions", "scale", "rotate",
                           "translate", "tex_scale", "tex_rotate", "tex_offset", "file"});
    SceneObject o;
    const std::string kind = getString(c, t, path, "mesh", "");
    // Tessellation keys belong to one mesh kind each.
    const std::pair<const char*, const char*> owner[] = {
        {"subdiv", "teapot"}, {"slices", "sphere"}, {"stacks", "sphere"}, {"major_radius", "torus"},
        {"minor_radius", "torus"}, {"segments", "torus"}, {"half_size", "plane"}, {"divisions", "plane"},
        {"file", "obj"}};
    for (const auto& [key, mk] : owner)
        if (find(t, key) && kind != mk)
            c.fail(find(t, key), join(path, key), std::string("belongs to mesh = \"") + mk + "\", not \"" + kind + "\"");
    // Every value is checked first; the meshes are built only when wanted (c.meshes), which
    // is what a parse costs (the animation keys are checked without them).
    std::function<Mesh()> make;
    if (kind == "teapot") {
        const int subdiv = getInt(c, t, path, "subdiv", 4, 1, 64);
        make = [=] { return makeTeapot(subdiv); };
    } else if (kind == "cube") {
        make = [] { return makeCube(); };
    } else if (kind == "sphere") {
        const int slices = getInt(c, t, path, "slices", 24, 3, 1024), stacks = getInt(c, t, path, "stacks", 12, 2, 1024);
        make = [=] { return makeSphere(slices, stacks); };
    } else if (kind == "torus") {
        int seg = getInt(c, t, path, "segments", 32, 3, 1024);
        const double R = getNumber(c, t, path, "major_radius", 1.0), r = getNumber(c, t, path, "minor_radius", 0.4);
        if (R <= 0) c.fail(find(t, "major_radius"), join(path, "major_radius"), "must be positive");
        if (r <= 0) c.fail(find(t, "minor_radius"), join(path, "minor_radius"), "must be positive");
        make = [=] { return makeTorus(R, r, seg, std::max(3, seg / 2)); };
    } else if (kind == "plane") {
        double hs = getNumber(c, t, path, "half_size", 1.0);
        if (hs <= 0) c.fail(find(t, "half_size"), join(path, "half_size"), "must be positive");
        const int div = getInt(c, t, path, "divisions", 1, 1, 1024);
        make = [=] { return makePlane(hs, div); };
    } else if (kind == "obj") {
        // A Wavefront OBJ file, relative to the scene file's folder.
        const toml::node* fn = find(t, "file") ? find(t, "file") : &t;
        const std::string file = getString(c, t, path, "file", "");
        if (file.empty()) c.fail(fn, join(path, "file"), "mesh = \"obj\" needs file = \"NAME.obj\"");
        const std::string full = file[0] == '/' ? file : (std::filesystem::path(c.file).parent_path() / file).string();
        o.meshSource = c.at(fn, join(path, "file")) + ": " + full;
        make = [&c, fn, full, field = join(path, "file")] {
            // The reader's InputError names the file (and line): "PATH:LINE: KEYWORD: what".
            try {
                ObjLimits lim;
                lim.maxCoord = kMaxSceneNumber;
                lim.maxTriangles = kMaxSceneTriangles - std::min(c.triangles, kMaxSceneTriangles);
                if (c.triangles > 0)
                    lim.triangleLimit = "what the scene's " + std::to_string(kMaxSceneTriangles) +
                                        "-triangle limit leaves after the objects above";
                return loadObjMesh(full, lim);
            } catch (const std::runtime_error& e) {
                c.fail(fn, field, e.what());
            }
        };
    } else {
        c.fail(find(t, "mesh") ? find(t, "mesh") : &t, join(path, "mesh"),
               "unknown mesh '" + kind + "' (expected teapot, cube, sphere, torus, plane or obj)");
    }
    o.name = kind;
    if (o.meshSource.empty())
        o.meshSource = c.at(find(t, "mesh") ? find(t, "mesh") : &t, join(path, "mesh")) + ": '" + kind + "'";
    const std::string texName = getString(c, t, path, "texture", "");
    auto it = textureIndex.find(texName);
    if (it == textureIndex.end())
        c.fail(find(t, "texture") ? find(t, "texture") : &t, join(path, "texture"),
               "no texture named '" + texName + "' in [textures]");
    o.texture = it->second;
    o.layer = getInt(c, t, path, "layer", 0, 0, 15);
    // Solid texture space: s = tex_rotate(tex_scale * object position) + tex_offset.
    glm::dmat4 texMap = placement(c, t, path, "tex_scale", "tex_rotate", "tex_offset");
    glm::dmat4 world = placement(c, t, path, "scale", "rotate", "translate");
    if (c.meshes) o.mesh = make().transformed(world, texMap);
    return o;
}

toml::table parseToml(const std::string& text, const std::string& path) {
    try {
        return toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        std::ostringstream os;
        os << path << ":" << e.source().begin.line << ":" << e.source().begin.column << ": "
           << e.description();
        throw InputError(os.str());
    }
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}


// The message of an error raised by the scene parser, without its leading "FILE(:LINE): ".
std::string innerMessage(const std::string& what, const std::string& file) {
    if (what.rfind(file, 0) != 0) return what;
    size_t p = what.find(": ", file.size());
    return p == std::string::npos ? what : what.substr(p + 2);
}

Scene buildScene(const Ctx& c, const toml::table& root, const std::string& path, int width, int height) {
    // A scene file is reported whole: each block (the top level's keys, image, camera, every
    // texture, every object) is checked on its own, its first error recorded, and every error is
    // thrown at the end, one line each. A texture that fails still holds its name, so the objects
    // that use it are not reported again for it.
    std::vector<std::string> errors;
    const auto each = [&errors](auto&& check) {
        try {
            check();
        } catch (const InputError& e) {
            if (std::find(errors.begin(), errors.end(), e.what()) == errors.end()) errors.push_back(e.what());
        }
    };
    Scene sc;
    sc.path = path;
    each([&] { checkKeys(c, root, "", {"title", "image", "camera", "textures", "objects", "animation"}); });
    each([&] { sc.title = getString(c, root, "", "title", path); });

    each([&] {
        const toml::table& img = requireTable(c, root, "", "image");
        checkKeys(c, img, "image", {"width", "height", "background"});
        // The file's size is checked even when the caller overrides it (--size).
        const int fileW = getInt(c, img, "image", "width", 512, 1, kMaxImageSide);
        const int fileH = getInt(c, img, "image", "height", 512, 1, kMaxImageSide);
        if (int64_t(fileW) * fileH > kMaxImagePixels)
            c.fail(find(img, "width") ? find(img, "width") : &img, "image",
                   std::to_string(fileW) + " x " + std::to_string(fileH) + " pixels: at most " +
                       std::to_string(kMaxImagePixels) + " pixels (4096 x 4096; about 140 bytes each)");
        sc.camera.width = width > 0 ? width : fileW;
        sc.camera.height = height > 0 ? height : fileH;
        if (int64_t(sc.camera.width) * sc.camera.height > kMaxImagePixels)
            throw InputError("--size: " + std::to_string(sc.camera.width) + " x " + std::to_string(sc.camera.height) +
                             " pixels: at most " + std::to_string(kMaxImagePixels) +
                             " pixels (4096 x 4096; about 140 bytes each)");
        sc.background = getColor(c, img, "image", "background", sc.background);
    });

    each([&] {
        const toml::table& cam = requireTable(c, root, "", "camera");
        checkKeys(c, cam, "camera", {"eye", "target", "up", "fovy", "near"});
        sc.camera.eye = getVec3(c, cam, "camera", "eye", sc.camera.eye);
        sc.camera.target = getVec3(c, cam, "camera", "target", sc.camera.target);
        sc.camera.up = getVec3(c, cam, "camera", "up", sc.camera.up);
        sc.camera.fovyDeg = getNumber(c, cam, "camera", "fovy", sc.camera.fovyDeg);
        sc.camera.nearPlane = getNumber(c, cam, "camera", "near", sc.camera.nearPlane);
        if (sc.camera.fovyDeg <= 0 || sc.camera.fovyDeg >= 180)
            c.fail(find(cam, "fovy"), "camera.fovy", "must be in (0, 180) degrees");
        if (sc.camera.nearPlane <= 0) c.fail(find(cam, "near"), "camera.near", "must be positive");
        if (glm::length(sc.camera.target - sc.camera.eye) == 0.0)
            c.fail(&cam, "camera.target", "must differ from camera.eye");
        if (glm::length(glm::cross(sc.camera.target - sc.camera.eye, sc.camera.up)) == 0.0)
            c.fail(&cam, "camera.up", "must not be parallel to the view direction");
    });

    std::map<std::string, int> textureIndex;
    bool texturesRead = false;
    each([&] {
        const toml::table& texs = requireTable(c, root, "", "textures");
        texturesRead = true;
        std::set<std::tuple<int, int, uint32_t>> tileSets;  // the subband tiles the scene builds
        size_t tileBytes = 0;
        for (auto&& [k, v] : texs) {
            Texture tex;
            each([&] {
                std::string tp = "textures." + std::string(k.str());
                if (!v.is_table()) c.fail(&v, tp, "expected a table");
                tex = parseTextureTable(c, *v.as_table(), tp);
                const NoiseOptions& no = tex.noise;
                if (no.basis == NoiseBasis::Subband && tileSets.insert({no.orientations, no.tileSize, no.seed}).second) {
                    tileBytes += subbandTileBytes(no.orientations, no.tileSize);
                    if (tileBytes > kSubbandMaxSceneBytes)
                        c.fail(find(*v.as_table(), "noise"), join(tp, "noise"),
                               "the scene's subband tiles (one set per seed, orientations, tile_size) would take " +
                                   std::to_string(tileBytes >> 20) + " MiB (at most " +
                                   std::to_string(kSubbandMaxSceneBytes >> 20) + ")");
                }
            });
            tex.name = std::string(k.str());
            textureIndex[tex.name] = static_cast<int>(sc.textures.size());
            sc.textures.push_back(std::move(tex));
        }
    });

    each([&] {
        const toml::node* on = find(root, "objects");
        if (!on || !on->is_array_of_tables())
            c.fail(on ? on : &root, "objects", "expected one or more [[objects]] tables");
        if (!texturesRead) return;   // every object would be reported for its texture again
        auto oa = on->as_array();
        size_t triangles = 0;
        for (size_t i = 0; i < oa->size(); ++i) {
            const std::string op = "objects[" + std::to_string(i) + "]";
            bool built = false;
            each([&] {
                sc.objects.push_back(parseObject(c, *oa->get(i)->as_table(), op, textureIndex));
                built = true;
            });
            if (!built) continue;
            triangles += sc.objects.back().mesh.triangles.size();
            c.triangles = triangles;
            if (triangles > kMaxSceneTriangles)
                c.fail(oa->get(i), op,
                       "the scene's meshes exceed " + std::to_string(kMaxSceneTriangles) +
                           " triangles (lower slices, stacks, segments, divisions or subdiv)");
        }
    });
    if (!errors.empty()) {
        std::string all;
        for (const std::string& e : errors) all += (all.empty() ? "" : "\n") + e;
        throw InputError(all);
    }
    return sc;
}

}  // namespace

int Scene::layers() const {
    int n = 1;
    for (const auto& o : objects) n = std::max(n, o.layer + 1);
    return n;
}

std::vector<double> Track::at(double t) const {
    if (t <= keys.front().t) return keys.front().value;
    if (t >= keys.back().t) return keys.back().value;
    size_t k = 1;
    while (keys[k].t < t) ++k;   // keys[k-1].t < t <= keys[k].t
    const TrackKey &a = keys[k - 1], &b = keys[k];
    const double u = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1.0;
    std::vector<double> v(a.value.size());
    for (size_t i = 0; i < v.size(); ++i) v[i] = a.value[i] + (b.value[i] - a.value[i]) * u;
    return v;
}

namespace {

// The scene of a file (c.meshes/c.tables false: checked only), every animation key checked.
Scene parseSceneWith(const Ctx& c, const std::string& text, const std::string& path, int width, int height) {
    toml::table root = parseToml(text, path);
    Animation an = parseAnimation(c, root);
    Scene sc = buildScene(c, root, path, width, height);
    // Every track at every key, alone, must give a valid scene (the scene parser's checks).
    for (size_t i = 0; i < an.tracks.size(); ++i)
        for (size_t k = 0; k < an.tracks[i].keys.size(); ++k) {
            toml::table r = root;
            applyTrack(r, an.tracks[i], an.tracks[i].keys[k].t);
            try {
                Ctx check = c;
                check.meshes = false;
                check.tables = false;
                buildScene(check, r, path, 1, 1);
            } catch (const InputError& e) {
                const toml::node* kn = root["animation"]["track"][i]["keys"][k].node();
                throw inputError(path, lineOf(kn),
                                 "animation.track[" + std::to_string(i) + "].keys[" + std::to_string(k) + "]",
                                 innerMessage(e.what(), path));
            }
        }
    sc.animation = std::move(an);
    return sc;
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& path, int width, int height) {
    return parseSceneWith(Ctx{path}, text, path, width, height);
}

void checkScene(const std::string& text, const std::string& path) {
    Ctx c{path};
    c.meshes = false;
    c.tables = false;
    parseSceneWith(c, text, path, 0, 0);
}

Scene parseSceneAt(const std::string& text, const std::string& path, double t, int width, int height) {
    if (!std::isfinite(t) || t < 0 || t > 1) throw InputError(path + ": time " + shortNumber(t) + " is not in [0, 1]");
    const Ctx c{path};
    toml::table root = parseToml(text, path);
    Animation an = parseAnimation(c, root);
    for (const Track& tr : an.tracks) applyTrack(root, tr, t);
    try {
        Scene sc = buildScene(c, root, path, width, height);
        sc.animation = std::move(an);
        return sc;
    } catch (const InputError& e) {
        std::ostringstream os;
        os << path << ": animation at t = " << t << ": " << innerMessage(e.what(), path);
        throw InputError(os.str());
    }
}

Scene loadScene(const std::string& path, int width, int height) {
    return parseScene(readFile(path), path, width, height);
}

Scene loadSceneAt(const std::string& path, double t, int width, int height) {
    return parseSceneAt(readFile(path), path, t, width, height);
}

Texture parseTexture(const std::string& text, const std::string& path) {
    const Ctx c{path};
    toml::table root = parseToml(text, path);
    Texture tex = parseTextureTable(c, root, "");
    tex.name = path;
    return tex;
}

void checkTexture(const std::string& text, const std::string& path) {
    Ctx c{path};
    c.tables = false;
    parseTextureTable(c, parseToml(text, path), "");
}

Texture loadTexture(const std::string& path) { return parseTexture(readFile(path), path); }

}  // namespace pst
