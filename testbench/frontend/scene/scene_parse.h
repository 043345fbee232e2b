// The scene parser's helpers, shared by scene.cpp (scenes, objects, time tracks) and
// scene_texture.cpp (texture blocks, colour maps): typed, range-checked reads of TOML nodes,
// every error "FILE:LINE: FIELD: what". Internal to the scene parser.
#pragma once

#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <toml++/toml.h>

#include "scene.h"

namespace pst::scene_detail {

// Error reporting: every message is "file:line: field: what".
struct Ctx {
    std::string file;
    bool meshes = true;   // false: check the objects' keys and values only, build no meshes
    bool tables = true;   // false: check the colour maps' keys and values only, build no tables
    // Triangles of the objects built so far: an OBJ file may add what kMaxSceneTriangles leaves,
    // refused while it is read (so the scene's meshes never hold more).
    mutable size_t triangles = 0;

    // "FILE:LINE: FIELD" of node n (":LINE" when the node has a line), a message's prefix.
    std::string at(const toml::node* n, const std::string& field) const { return inputWhere(file, lineOf(n), field); }

    [[noreturn]] void fail(const toml::node* n, const std::string& field,
                           const std::string& what) const {
        throw inputError(file, lineOf(n), field, what);
    }
};

inline std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
}

// Unknown keys are errors, so a typo does not silently fall back to a default.
inline void checkKeys(const Ctx& c, const toml::table& t, const std::string& path,
               std::initializer_list<const char*> allowed) {
    for (auto&& [k, v] : t) {
        bool ok = false;
        for (const char* a : allowed) ok = ok || k.str() == a;
        if (!ok) {
            std::string list;
            for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
            c.fail(&v, join(path, std::string(k.str())), "unknown key (expected one of: " + list + ")");
        }
    }
}

inline double asNumber(const Ctx& c, const toml::node& n, const std::string& field) {
    double v;
    if (auto i = n.as_integer()) v = static_cast<double>(i->get());
    else if (auto f = n.as_floating_point()) v = f->get();
    else c.fail(&n, field, "expected a number");
    if (!std::isfinite(v)) c.fail(&n, field, "NaN and infinite numbers are not allowed");
    // Every number of a scene is a coordinate, a coefficient, an angle or a colour: a bound far
    // beyond any of them keeps products and squares finite (no NaN or infinite pixels).
    if (std::abs(v) > kMaxSceneNumber)
        c.fail(&n, field, "magnitude must be at most 1e6 (got " + shortNumber(v) + ")");
    return v;
}

inline const toml::node* find(const toml::table& t, const char* key) { return t.get(key); }

inline double getNumber(const Ctx& c, const toml::table& t, const std::string& path, const char* key,
                 double def) {
    const toml::node* n = find(t, key);
    return n ? asNumber(c, *n, join(path, key)) : def;
}

inline double requireNumber(const Ctx& c, const toml::table& t, const std::string& path, const char* key) {
    const toml::node* n = find(t, key);
    if (!n) c.fail(&t, join(path, key), "missing");
    return asNumber(c, *n, join(path, key));
}

inline int getInt(const Ctx& c, const toml::table& t, const std::string& path, const char* key, int def,
           int lo, int hi) {
    const toml::node* n = find(t, key);
    if (!n) return def;
    auto i = n->as_integer();
    if (!i) c.fail(n, join(path, key), "expected an integer");
    if (i->get() < lo || i->get() > hi)
        c.fail(n, join(path, key),
               "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                   std::to_string(i->get()) + ")");
    return static_cast<int>(i->get());
}

inline std::vector<double> asNumbers(const Ctx& c, const toml::node& n, const std::string& field,
                              size_t minCount, size_t maxCount) {
    auto a = n.as_array();
    if (!a) c.fail(&n, field, "expected an array of numbers");
    if (a->size() < minCount || a->size() > maxCount) {
        std::string want = minCount == maxCount ? std::to_string(minCount)
                                                : std::to_string(minCount) + " to " + std::to_string(maxCount);
        c.fail(&n, field, "expected " + want + " numbers, got " + std::to_string(a->size()));
    }
    std::vector<double> out;
    for (size_t i = 0; i < a->size(); ++i)
        out.push_back(asNumber(c, *a->get(i), field + "[" + std::to_string(i) + "]"));
    return out;
}

inline glm::dvec3 getVec3(const Ctx& c, const toml::table& t, const std::string& path, const char* key,
                   glm::dvec3 def) {
    const toml::node* n = find(t, key);
    if (!n) return def;
    auto v = asNumbers(c, *n, join(path, key), 3, 3);
    return {v[0], v[1], v[2]};
}

// A number (uniform) or a 3-vector.
inline glm::dvec3 getScale(const Ctx& c, const toml::table& t, const std::string& path, const char* key) {
    const toml::node* n = find(t, key);
    if (!n) return glm::dvec3(1.0);
    if (n->is_array()) return getVec3(c, t, path, key, glm::dvec3(1.0));
    return glm::dvec3(asNumber(c, *n, join(path, key)));
}

inline glm::dvec4 getColor(const Ctx& c, const toml::table& t, const std::string& path, const char* key,
                    glm::dvec4 def) {
    const toml::node* n = find(t, key);
    if (!n) return def;
    auto v = asNumbers(c, *n, join(path, key), 3, 4);
    for (double x : v)
        if (x < 0.0 || x > 1.0) c.fail(n, join(path, key), "colour components must be in [0, 1]");
    return {v[0], v[1], v[2], v.size() == 4 ? v[3] : 1.0};
}

inline std::string getString(const Ctx& c, const toml::table& t, const std::string& path, const char* key,
                      const std::string& def) {
    const toml::node* n = find(t, key);
    if (!n) return def;
    auto s = n->as_string();
    if (!s) c.fail(n, join(path, key), "expected a string");
    return s->get();
}

inline const toml::table& requireTable(const Ctx& c, const toml::table& t, const std::string& path,
                                const char* key) {
    const toml::node* n = find(t, key);
    if (!n) c.fail(&t, join(path, key), "missing table");
    if (!n->is_table()) c.fail(n, join(path, key), "expected a table");
    return *n->as_table();
}

// Enum fields go through the model's own parsers, so the names live in one place.
template <typename E>
E getEnum(const Ctx& c, const toml::table& t, const std::string& path, const char* key, E def,
          bool (*parse)(const std::string&, E*), const char* choices) {
    const toml::node* n = find(t, key);
    if (!n) return def;
    std::string s = getString(c, t, path, key, "");
    E out;
    if (!parse(s, &out)) c.fail(n, join(path, key), "unknown value '" + s + "' (expected " + choices + ")");
    return out;
}

ColorMap parseColorMap(const Ctx& c, const toml::table& t, const std::string& path);
Texture parseTextureTable(const Ctx& c, const toml::table& t, const std::string& path);

// The time track (scene_animation.cpp): [animation] read and checked against the tree; one
// track's value at time t written into the tree.
Animation parseAnimation(const Ctx& c, toml::table& root);
void applyTrack(toml::table& root, const Track& tr, double t);

}  // namespace pst::scene_detail
