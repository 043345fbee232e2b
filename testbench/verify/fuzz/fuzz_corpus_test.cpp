// Replays the fuzzers' kept inputs (testbench/verify/fuzz/corpus/<target>/: the minimized corpora of the
// libFuzzer runs; testbench/verify/fuzz/regress/<target>/: inputs that once crashed) through the same
// entry points as the fuzz targets (fuzz_inputs.h), so a parser change that crashes on one of
// them fails ctest (and the sanitizer build reports memory errors on them). For scene files the
// check-only parse (checkScene) must also agree with the full parse (parseScene).
#include "fuzz_inputs.h"
#include "source_dir.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

namespace pst {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Every kept input of `target`; fails when there is none (the corpus went missing).
int replay(const std::string& target, const std::function<void(const std::string&)>& run) {
    int n = 0;
    for (const char* kind : {"corpus", "regress"}) {
        const fs::path dir = fs::path(sourceDir()) / "testbench/verify/fuzz" / kind / target;
        if (!fs::is_directory(dir)) continue;
        for (const auto& e : fs::directory_iterator(dir)) {
            if (!e.is_regular_file()) continue;
            SCOPED_TRACE(e.path().string());
            EXPECT_NO_THROW(run(slurp(e.path())));
            ++n;
        }
    }
    EXPECT_GT(n, 0) << "no kept inputs for " << target;
    return n;
}

TEST(FuzzCorpus, Scene) { replay("scene", fuzz::scene); }
TEST(FuzzCorpus, Texture) { replay("texture", fuzz::texture); }
TEST(FuzzCorpus, Fragments) { replay("fragments", fuzz::fragments); }
TEST(FuzzCorpus, Profile) { replay("profile", fuzz::profile); }
TEST(FuzzCorpus, Obj) { replay("obj", fuzz::obj); }

// The OBJ corpus holds meshes the reader accepts and inputs it refuses, so replaying it is not
// vacuous either way.
TEST(FuzzCorpus, ObjAcceptedAndRefused) {
    int accepted = 0, refused = 0;
    replay("obj", [&](const std::string& text) {
        std::istringstream in(text);
        try {
            (void)readObjMesh(in, "fuzz.obj");
            ++accepted;
        } catch (const InputError&) {
            ++refused;
        }
    });
    EXPECT_GT(accepted, 0);
    EXPECT_GT(refused, 0);
}

// checkScene refuses exactly what parseScene refuses, with the same message (the triangle
// bound aside, which needs the meshes: no kept input comes near it).
TEST(FuzzCorpus, SceneCheckAgreesWithParse) {
    int accepted = 0, refused = 0;
    replay("scene", [&](const std::string& text) {
        std::string full, check;
        try {
            parseScene(text, "fuzz.toml", 8, 8);
        } catch (const InputError& e) {
            full = e.what();
        }
        try {
            checkScene(text, "fuzz.toml");
        } catch (const InputError& e) {
            check = e.what();
        }
        EXPECT_EQ(full, check);
        ++(full.empty() ? accepted : refused);
    });
    // Both kinds are in the corpus, so the comparison is not vacuous.
    EXPECT_GT(accepted, 0);
    EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace pst
