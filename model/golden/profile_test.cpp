// The profile reader against the contract (rtl/contract.toml -> contract.h): the model's enums
// in the contract's order, shipped profiles read, each cross-constraint names its field.
#include "profile.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "contract.h"
#include "input_error.h"

namespace pst {
namespace {

// rtl/configs/reduced.toml (PST_SOURCE_DIR: set by ctest; the build's source dir otherwise).
std::string reducedPath() {
    const char* env = std::getenv("PST_SOURCE_DIR");
    return profilePath("reduced", env ? env : PST_SOURCE_DIR_DEFAULT);
}

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The model's enums (model/noise.h, model/texture.h, profile.h) are cast from the contract's
// indices: their order must be the contract's.
TEST(Profile, ModelEnumsFollowTheContractOrder) {
    for (int i = 0; i < int(std::size(contract::kNoiseInterpNames)); ++i) {
        NoiseInterp e;
        ASSERT_TRUE(parseNoiseInterp(contract::kNoiseInterpNames[i], &e));
        EXPECT_EQ(int(e), i);
    }
    for (int i = 0; i < int(std::size(contract::kNoiseCornerNames)); ++i) {
        NoiseCorner e;
        ASSERT_TRUE(parseNoiseCorner(contract::kNoiseCornerNames[i], &e));
        EXPECT_EQ(int(e), i);
    }
    for (int i = 0; i < int(std::size(contract::kNoiseHashNames)); ++i) {
        NoiseHash e;
        ASSERT_TRUE(parseNoiseHash(contract::kNoiseHashNames[i], &e));
        EXPECT_EQ(int(e), i);
    }
    for (int i = 0; i < int(std::size(contract::kFilterNormNames)); ++i) {
        GradNorm e;
        ASSERT_TRUE(parseGradNorm(contract::kFilterNormNames[i], &e));
        EXPECT_EQ(int(e), i);
    }
    EXPECT_STREQ(contract::kDatapathNames[int(Datapath::Parallel)], "parallel");
    EXPECT_STREQ(contract::kDatapathNames[int(Datapath::Serial)], "serial");
}

TEST(Profile, ReadsReduced) {
    const Profile p = loadProfile(reducedPath());
    EXPECT_EQ(p.name, "reduced");
    EXPECT_EQ(p.octaves, 5);
    EXPECT_EQ(p.noiseUnits, 1);
    EXPECT_EQ(p.noiseSteps, 4);
    EXPECT_EQ(p.datapath, Datapath::Serial);
    EXPECT_EQ(p.noise.hash, NoiseHash::Rayshade4096);
    EXPECT_EQ(p.filterNorm, GradNorm::Euclid);
    EXPECT_EQ(p.coord.intBits, 10);
    EXPECT_EQ(p.coord.fracBits, 12);
    EXPECT_EQ(p.grad.intBits, 12);
    EXPECT_EQ(p.grad.fracBits, 8);
    EXPECT_EQ(p.widthFrac, 4);
}

// One edit of reduced.toml, the error it must give (file:line: field: what).
void expectError(const std::string& from, const std::string& to, const std::string& expected) {
    std::string text = readFile(reducedPath());
    const auto at = text.find("\n" + from);  // the key's own line, not a comment
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at + 1, from.size(), to);
    try {
        parseProfile(text, "p.toml");
        ADD_FAILURE() << "accepted: " << to;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).rfind("p.toml:", 0), 0u) << e.what();
    }
}

TEST(Profile, RejectsWhatTheContractRejects) {
    expectError("noise_units = 1", "noise_units = 3", "pipeline.noise_units: must divide pipeline.octaves");
    expectError("noise_steps = 4", "noise_steps = 2", "pipeline.datapath: serial needs pipeline.noise_steps >= 4");
    expectError("noise_steps = 4", "noise_steps = 3", "pipeline.noise_steps: must be 1, 2, 4 or 8");
    expectError("octaves = 5", "octaves = 17", "pipeline.octaves: must be in [1, 16]");
    expectError("datapath = \"serial\"", "datapath = \"fast\"", "pipeline.datapath: unknown value 'fast'");
    expectError("offset     = { int = 13, frac = 8 }", "offset     = { int = 2, frac = 21 }",
                "formats.offset: frac must be at most formats.matrix.frac + formats.coord.frac");
    expectError("coord      = { int = 10, frac = 12 }", "coord      = { int = 30, frac = 12 }",
                "formats.coord: int + frac must be at most 40");
    expectError("width_frac = 4", "width_frac = 25", "formats.width_frac: must be in [0, 24]");
}

}  // namespace
}  // namespace pst
