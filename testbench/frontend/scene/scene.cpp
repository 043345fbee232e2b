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


// --- Time track: [animation] frames, fps, [[animation.track]] field + keys -----------------
struct Seg {
    std::string key;
    int index = -1;    // key[N]
    bool all = false;  // key[*]
};

bool parseFieldPath(const std::string& s, std::vector<Seg>* out) {
    std::stringstream ss(s);
    std::string part;
    while (std::getline(ss, part, '.')) {
        Seg g;
        size_t b = part.find('[');
        g.key = part.substr(0, b);
        if (g.key.empty()) return false;
        if (b != std::string::npos) {
            if (part.back() != ']') return false;
            std::string ix = part.substr(b + 1, part.size() - b - 2);
            if (ix == "*") g.all = true;
            else {
                if (ix.empty() || ix.size() > 4 || ix.find_first_not_of("0123456789") != std::string::npos) return false;
                g.index = std::stoi(ix);
            }
        }
        out->push_back(g);
    }
    return !out->empty() && !s.empty() && s.back() != '.';
}

// The tables that hold the path's last key (several with [*]); "" or what does not resolve.
std::vector<toml::table*> leafTables(toml::table& root, const std::vector<Seg>& segs, std::string* err) {
    std::vector<toml::table*> cur{&root};
    for (size_t i = 0; i + 1 < segs.size(); ++i) {
        const Seg& g = segs[i];
        std::vector<toml::table*> next;
        for (toml::table* t : cur) {
            toml::node* n = t->get(g.key);
            if (!n) { *err = "'" + g.key + "' is not in the file"; return {}; }
            if (g.all || g.index >= 0) {
                toml::array* a = n->as_array();
                if (!a) { *err = "'" + g.key + "' is not an array"; return {}; }
                if (g.index >= int(a->size())) {
                    *err = "'" + g.key + "' has " + std::to_string(a->size()) + " entries";
                    return {};
                }
                for (size_t k = 0; k < a->size(); ++k) {
                    if (g.index >= 0 && int(k) != g.index) continue;
                    toml::table* e = a->get(k)->as_table();
                    if (!e) { *err = "'" + g.key + "' entries are not tables"; return {}; }
                    next.push_back(e);
                }
            } else {
                toml::table* e = n->as_table();
                if (!e) { *err = "'" + g.key + "' is not a table (index it: " + g.key + "[N] or [*])"; return {}; }
                next.push_back(e);
            }
        }
        cur = std::move(next);
    }
    if (segs.back().all || segs.back().index >= 0) {
        *err = "the last part names a field, not an array entry";
        return {};
    }
    return cur;
}

std::vector<Seg> trackPath(const Track& tr) {
    std::vector<Seg> segs;
    parseFieldPath(tr.field, &segs);
    return segs;
}

void applyTrack(toml::table& root, const Track& tr, double t) {
    std::string err;
    const std::vector<Seg> segs = trackPath(tr);
    const std::vector<double> v = tr.at(t);
    for (toml::table* tb : leafTables(root, segs, &err)) {
        if (v.size() == 1) tb->insert_or_assign(segs.back().key, v[0]);
        else {
            toml::array a;
            for (double x : v) a.push_back(x);
            tb->insert_or_assign(segs.back().key, std::move(a));
        }
    }
}

Animation parseAnimation(const Ctx& c, toml::table& root) {
    Animation an;
    const toml::node* node = find(root, "animation");
    if (!node) return an;
    const toml::table* at = node->as_table();
    if (!at) c.fail(node, "animation", "expected a table");
    checkKeys(c, *at, "animation", {"frames", "fps", "track"});
    an.frames = getInt(c, *at, "animation", "frames", 0, 1, 10000);
    an.fps = getNumber(c, *at, "animation", "fps", an.fps);
    if (an.fps <= 0 || an.fps > 240) c.fail(find(*at, "fps"), "animation.fps", "must be in (0, 240]");
    const toml::node* tn = find(*at, "track");
    if (!tn) c.fail(at, "animation.track", "missing: one or more [[animation.track]] tables");
    const toml::array* ta = tn->as_array();
    if (!ta || !ta->is_array_of_tables() || ta->empty())
        c.fail(tn, "animation.track", "expected one or more [[animation.track]] tables");
    if (ta->size() > 256) c.fail(tn, "animation.track", "at most 256 tracks");
    for (size_t i = 0; i < ta->size(); ++i) {
        const std::string tp = "animation.track[" + std::to_string(i) + "]";
        const toml::table& tt = *ta->get(i)->as_table();
        checkKeys(c, tt, tp, {"field", "keys"});
        Track tr;
        tr.where = inputWhere(c.file, lineOf(&tt));
        const toml::node* fn = find(tt, "field");
        if (!fn) c.fail(&tt, join(tp, "field"), "missing");
        tr.field = getString(c, tt, tp, "field", "");
        std::vector<Seg> segs;
        if (!parseFieldPath(tr.field, &segs))
            c.fail(fn, join(tp, "field"), "'" + tr.field + "' is not a field path (e.g. camera.eye, "
                                           "textures.NAME.octaves[*].offset, objects[0].tex_rotate)");
        if (segs[0].key != "camera" && segs[0].key != "textures" && segs[0].key != "objects")
            c.fail(fn, join(tp, "field"), "'" + tr.field + "': only camera, textures and objects fields can be animated");
        std::string err;
        std::vector<toml::table*> leaves = leafTables(root, segs, &err);
        if (!err.empty()) c.fail(fn, join(tp, "field"), "'" + tr.field + "': " + err);
        // An existing field fixes the number of values; a missing one (e.g. tex_rotate) is
        // checked by the scene parser at every key below.
        size_t want = 0;
        for (toml::table* tb : leaves)
            if (const toml::node* leaf = tb->get(segs.back().key)) {
                if (leaf->is_number()) want = 1;
                else if (leaf->is_array()) want = leaf->as_array()->size();
                else c.fail(fn, join(tp, "field"), "'" + tr.field + "' is not a number or an array of numbers");
            }
        const toml::node* kn = find(tt, "keys");
        if (!kn) c.fail(&tt, join(tp, "keys"), "missing");
        const toml::array* ka = kn->as_array();
        if (!ka || ka->empty()) c.fail(kn, join(tp, "keys"), "expected an array of [t, value...] keys");
        if (ka->size() > 4096) c.fail(kn, join(tp, "keys"), "at most 4096 keys");
        for (size_t k = 0; k < ka->size(); ++k) {
            const std::string kp = join(tp, "keys") + "[" + std::to_string(k) + "]";
            std::vector<double> v = asNumbers(c, *ka->get(k), kp, 2, 5);
            TrackKey key{v[0], std::vector<double>(v.begin() + 1, v.end())};
            if (key.t < 0 || key.t > 1) c.fail(ka->get(k), kp, "time must be in [0, 1] (the whole sequence)");
            if (!tr.keys.empty() && key.t < tr.keys.back().t) c.fail(ka->get(k), kp, "times must not decrease");
            if (want && key.value.size() != want)
                c.fail(ka->get(k), kp, "'" + tr.field + "' takes " + std::to_string(want) + " number(s), got " +
                                           std::to_string(key.value.size()));
            if (!tr.keys.empty() && key.value.size() != tr.keys[0].value.size())
                c.fail(ka->get(k), kp, "every key must have as many values as the first");
            tr.keys.push_back(std::move(key));
        }
        an.tracks.push_back(std::move(tr));
    }
    return an;
}

// The message of an error raised by the scene parser, without its leading "FILE(:LINE): ".
std::string innerMessage(const std::string& what, const std::string& file) {
    if (what.rfind(file, 0) != 0) return what;
    size_t p = what.find(": ", file.size());
    return p == std::string::npos ? what : what.substr(p + 2);
}

Scene buildScene(const Ctx& c, const toml::table& root, const std::string& path, int width, int height) {
    checkKeys(c, root, "", {"title", "image", "camera", "textures", "objects", "animation"});
    Scene sc;
    sc.path = path;
    sc.title = getString(c, root, "", "title", path);

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

    std::map<std::string, int> textureIndex;
    const toml::table& texs = requireTable(c, root, "", "textures");
    std::set<std::tuple<int, int, uint32_t>> tileSets;  // the subband tiles the scene builds
    size_t tileBytes = 0;
    for (auto&& [k, v] : texs) {
        std::string tp = "textures." + std::string(k.str());
        if (!v.is_table()) c.fail(&v, tp, "expected a table");
        Texture tex = parseTextureTable(c, *v.as_table(), tp);
        const NoiseOptions& no = tex.noise;
        if (no.basis == NoiseBasis::Subband && tileSets.insert({no.orientations, no.tileSize, no.seed}).second) {
            tileBytes += subbandTileBytes(no.orientations, no.tileSize);
            if (tileBytes > kSubbandMaxSceneBytes)
                c.fail(find(*v.as_table(), "noise"), join(tp, "noise"),
                       "the scene's subband tiles (one set per seed, orientations, tile_size) would take " +
                           std::to_string(tileBytes >> 20) + " MiB (at most " +
                           std::to_string(kSubbandMaxSceneBytes >> 20) + ")");
        }
        tex.name = std::string(k.str());
        textureIndex[tex.name] = static_cast<int>(sc.textures.size());
        sc.textures.push_back(std::move(tex));
    }

    const toml::node* on = find(root, "objects");
    if (!on || !on->is_array_of_tables())
        c.fail(on ? on : &root, "objects", "expected one or more [[objects]] tables");
    auto oa = on->as_array();
    size_t triangles = 0;
    for (size_t i = 0; i < oa->size(); ++i) {
        sc.objects.push_back(parseObject(c, *oa->get(i)->as_table(),
                                         "objects[" + std::to_string(i) + "]", textureIndex));
        triangles += sc.objects.back().mesh.triangles.size();
        c.triangles = triangles;
        if (triangles > kMaxSceneTriangles)
            c.fail(oa->get(i), "objects[" + std::to_string(i) + "]",
                   "the scene's meshes exceed " + std::to_string(kMaxSceneTriangles) +
                       " triangles (lower slices, stacks, segments, divisions or subdiv)");
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
