// One input of each parser under fuzzing (testbench/verify/fuzz): the libFuzzer targets call these, and
// fuzz_corpus_test replays the kept corpora and crash inputs through them. An input must either
// be accepted or refused with an InputError (`error: FILE:LINE: FIELD: ...`, exit 2 in the CLI);
// a crash, a sanitizer report or any other exception is a bug.
#pragma once

#include <sstream>
#include <string>

#include "fragments.h"
#include "input_error.h"
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

}  // namespace pst::fuzz
