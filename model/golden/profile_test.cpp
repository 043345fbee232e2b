// The profile reader against the contract (rtl/contract.toml -> contract.h): the model's enums
// in the contract's order, shipped profiles read, each cross-constraint names its field.
#include "profile.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "contract.h"
#include "input_error.h"
#include "source_dir.h"

namespace pst {
namespace {

// rtl/configs/reduced.toml (PST_SOURCE_DIR: set by ctest; the build's source tree otherwise).
std::string reducedPath() { return profilePath("reduced", sourceDir()); }

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

// The generated enums (contract.h) name the contract's values in its order, both ways.
TEST(Profile, GeneratedEnumsMatchTheContract) {
    const auto check = [](auto first, const auto& names) {
        using E = decltype(first);
        for (int i = 0; i < int(std::size(names)); ++i) {
            EXPECT_STREQ(contract::name(E(i)), names[i]);
            E e{};
            ASSERT_TRUE(contract::fromName(names[i], &e));
            EXPECT_EQ(int(e), i);
        }
        E e{};
        EXPECT_FALSE(contract::fromName("no_such_value", &e));
        EXPECT_STREQ(contract::name(E(int(std::size(names)))), "?");
    };
    check(Datapath{}, contract::kDatapathNames);
    check(NoiseInterp{}, contract::kNoiseInterpNames);
    check(NoiseCorner{}, contract::kNoiseCornerNames);
    check(NoiseHash{}, contract::kNoiseHashNames);
    check(NoiseWorleySearch{}, contract::kNoiseWorleySearchNames);
    check(GradNorm{}, contract::kFilterNormNames);
    check(FilterBandlimit{}, contract::kFilterBandlimitNames);
    EXPECT_EQ(int(NoiseHash::Perlin256), 2);
    EXPECT_EQ(int(GradNorm::L1), 2);
}

// ProfileParams' members by RTL parameter: every parameter reaches its own member.
TEST(Profile, ParamsByParameter) {
    const Profile full = loadNamedProfile("full", sourceDir());
    // The generated defaults are the defaults profile's (full.toml), like pst_pkg's *Default.
    EXPECT_EQ(profileDifference(Profile{}, full), "");
    ProfileParams p;
    for (int i = 0; i < contract::kNumParams; ++i) contract::setParam(p, contract::Param(i), 100 + i);
    for (int i = 0; i < contract::kNumParams; ++i) EXPECT_EQ(contract::paramValue(p, contract::Param(i)), 100 + i);
    EXPECT_EQ(p.octaves, 100 + contract::Octaves);
    EXPECT_EQ(p.grad.fracBits, 100 + contract::GradFrac);
    EXPECT_EQ(int(p.filterBandlimit), 100 + contract::FilterBandlimit);
    EXPECT_STREQ(contract::kParamNames[contract::NoiseWorleyOrder], "NoiseWorleyOrder");
}

// The contract's formulas (contract.h) on reduced: the docs/HARDWARE.md cycle table's row.
TEST(Profile, FormulasOfReduced) {
    const Profile p = loadProfile(reducedPath());
    EXPECT_EQ(p.widthIntBits(), 10);
    EXPECT_EQ(p.widthBits(), 14);
    EXPECT_EQ(contract::octave_cycles(p.octaves, p.noiseUnits, p.noiseSteps, int(p.datapath), p.noiseRegs, p.octaveRegs), 32);
    EXPECT_EQ(contract::quadric_cycles(int(p.datapath), p.quadric.width(), p.coord.width(), p.octaveRegs), 23);
    EXPECT_EQ(contract::width_cycles(int(p.datapath), int(p.filterNorm), p.log2Clut, p.widthFrac), 16);
    EXPECT_EQ(contract::colour_cycles(int(p.datapath), p.colourRegs), 6);
    EXPECT_EQ(p.cyclesPerPixel(), 32);
    static_assert(contract::w_width(8, 8) == 18, "constexpr");
}

// A profile argument: a file when it has a '/' or ends in .toml, else a name in rtl/configs.
TEST(Profile, NameOrFile) {
    EXPECT_FALSE(isProfileFile("full"));
    EXPECT_TRUE(isProfileFile("mine.toml"));
    EXPECT_TRUE(isProfileFile("dir/full"));
    EXPECT_EQ(profilePath("full", "/src"), "/src/rtl/configs/full.toml");
    EXPECT_EQ(profilePath("x/mine.toml", "/src"), "x/mine.toml");
}

TEST(Profile, ReadsReduced) {
    const Profile p = loadProfile(reducedPath());
    EXPECT_EQ(p.name, "reduced");
    EXPECT_EQ(p.octaves, 5);
    EXPECT_EQ(p.noiseUnits, 1);
    EXPECT_EQ(p.noiseSteps, 4);
    EXPECT_EQ(p.datapath, Datapath::Serial);
    EXPECT_EQ(p.noise.hash, NoiseHash::Rayshade);
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
    expectError("noise_units = 1", "noise_units = 3",
                "pipeline.noise_units: must divide pipeline.octaves on the serial datapath");
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

// A profile file is reported whole: every key's error on its own line (FILE:LINE: FIELD: what),
// a typo'd key beside them; the constraints between keys only once every key has a value.
TEST(Profile, ReportsEveryErrorNotOnlyTheFirst) {
    std::string text = readFile(reducedPath());
    for (auto [from, to] : {std::pair<std::string, std::string>{"octaves = 5", "octaves = 17"},
                            {"datapath = \"serial\"", "datapath = \"fast\""},
                            {"width_frac = 4", "width_frac = 25"}}) {
        const auto at = text.find("\n" + from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at + 1, from.size(), to);
    }
    text += "\n[pipeline2]\nx = 1\n";
    try {
        parseProfile(text, "p.toml");
        ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
        std::istringstream lines(e.what());
        std::vector<std::string> got;
        for (std::string line; std::getline(lines, line);) got.push_back(line);
        ASSERT_EQ(got.size(), 4u) << e.what();
        const std::string all = e.what();
        for (const char* want : {"pipeline.octaves: must be in [1, 16]", "pipeline.datapath: unknown value 'fast'",
                                 "formats.width_frac: must be in [0, 24]", "pipeline2: unknown section"})
            EXPECT_NE(all.find(want), std::string::npos) << want << " in\n" << all;
        for (const std::string& line : got) EXPECT_EQ(line.rfind("p.toml:", 0), 0u) << line;
    }
}

}  // namespace
}  // namespace pst
