// One input of each parser under fuzzing (testbench/verify/fuzz): the libFuzzer targets call these, and
// fuzz_corpus_test replays the kept corpora and crash inputs through them. An input must either
// be accepted or refused with an InputError (`error: FILE:LINE: FIELD: ...`, exit 2 in the CLI);
// a crash, a sanitizer report or any other exception is a bug.
#pragma once

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fragments.h"
#include "input_error.h"
#include "objmesh.h"
#include "profile.h"
#include "scene.h"

namespace pst::fuzz {

// Scene files: every check of parseScene without building meshes or colour tables (checkScene;
// building them is what made a scene parse cost milliseconds).
inline void scene(const std::string& text) {
    try {
        checkScene(text, "fuzz.toml");
    } catch (const InputError&) {
    }
}

// Texture blocks (`pst eval --texture`): every check of parseTexture, no colour tables.
inline void texture(const std::string& text) {
    try {
        checkTexture(text, "fuzz.toml");
    } catch (const InputError&) {
    }
}

// Fragment files.
inline void fragments(const std::string& text) {
    std::istringstream in(text);
    try {
        (void)readFragments(in, "fuzz.frag").size();
    } catch (const InputError&) {
    }
}

// Hardware profiles.
inline void profile(const std::string& text) {
    try {
        (void)parseProfile(text, "fuzz.toml").clutSize();
    } catch (const InputError&) {
    }
}

// OBJ meshes (objmesh.h, the strict reader): refused with an InputError, or a mesh whose every
// index names a vertex and every coordinate is finite and within the bound (anything else
// throws std::logic_error: a bug the fuzzer reports as a crash, the corpus test as a failure).
inline void obj(const std::string& text) {
    std::istringstream in(text);
    ObjLimits lim;
    lim.maxBytes = 1 << 20;
    Mesh m;
    try {
        m = readObjMesh(in, "fuzz.obj", lim);
    } catch (const InputError&) {
        return;
    }
    if (m.triangles.empty() || m.texcoords.size() != m.positions.size() || m.positions.size() > lim.maxVertices ||
        m.triangles.size() > lim.maxTriangles)
        throw std::logic_error("fuzz.obj: mesh accepted with no faces or inconsistent sizes");
    for (const glm::dvec3& p : m.positions)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(p[k]) || std::abs(p[k]) > lim.maxCoord)
                throw std::logic_error("fuzz.obj: coordinate accepted that is not finite or beyond the bound");
    for (const auto& t : m.triangles)
        for (uint32_t i : t)
            if (i >= m.positions.size()) throw std::logic_error("fuzz.obj: vertex index accepted out of range");
    (void)zeroAreaTriangles(m);
}

}  // namespace pst::fuzz
