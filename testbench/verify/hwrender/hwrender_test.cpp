// The RTL against the golden model, bit for bit: every paper scene through every verilated
// profile, constrained-random fragments and textures with random stalls, and a scoreboard
// self-test that perturbs one golden unit at a time.
#include "hwrender.h"

#include <cmath>
#include <cstdlib>
#include <random>

#include <gtest/gtest.h>

#include "driver.h"
#include "fragments.h"
#include "fixed.h"
#include "scoreboard.h"
#include "source_dir.h"

namespace pst {
namespace {

// The file each verilated profile was built from (rtl/configs, sim/test_profiles, ...).
Profile profile(const std::string& name) { return loadProfile(rtlProfilePath(name)); }

const char* kScenes[] = {"wood_teapot", "marble", "seascape", "fire", "planet", "moonrise", "zoneplate", "wood_torus",
                         "perlin2002", "worley", "seascape_subband_hw", "seascape_subband"};

// Whether profile p's noise unit computes every texture of the scene (its basis).
bool runsScene(const Profile& p, const Scene& scene) {
    for (const Texture& tex : scene.textures)
        if (!hardwareUnsupported(p, tex).empty()) return false;
    return true;
}

// A scene of the profile's basis (the perturbed-unit test's).
std::string basisScene(const Profile& p) {
    return p.noise.basis == NoiseBasis::Perlin2002 ? "perlin2002"
           : p.noise.basis == NoiseBasis::Worley   ? "worley"
           : p.noise.basis == NoiseBasis::Subband  ? (p.noiseSubbandOrientations == 8 ? "seascape_subband"
                                                                                        : "seascape_subband_hw")
                                                   : "marble";
}

class EveryProfile : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryProfile, EveryScene64x64MatchesGolden) {
    const Profile p = profile(GetParam());
    SimOptions so;
    so.seed = 7;
    so.inputGapRate = 0.1;
    so.outputStallRate = 0.2;
    int rendered = 0;
    for (const char* name : kScenes) {
        SCOPED_TRACE(name);
        Scene scene = loadScene(sourceDir() + "/scenes/" + name + ".toml", 64, 64);
        if (!runsScene(p, scene)) continue;  // another basis (regress skips it too)
        ++rendered;
        auto rtl = makeRtlModel(p.name, so);
        HwRenderResult r = renderHardware(scene, p, rtl.get());
        EXPECT_TRUE(r.passed) << r.scoreboard;
        EXPECT_EQ(r.mismatches, 0u);
        EXPECT_EQ(static_cast<long long>(r.pixels), r.fragments);
        EXPECT_GT(r.fragments, 100);
        std::printf("%-12s %-8s %5lld px  %6.3f cycles/px  PSNR %.2f dB  %.1f%% within 1 LSB\n", name,
                    p.name.c_str(), r.fragments, r.cyclesPerPixel, r.vsReference.psnr, r.vsReference.within1Lsb);
    }
    EXPECT_GE(rendered, p.noise.basis == NoiseBasis::Rayshade ? 8 : 1);
}

// A random texture within the profile's formats, with a random colour table.
Texture randomTexture(std::mt19937_64& rng, const Profile& p) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Texture t;
    t.name = "random";
    t.noise = p.noise;  // the profile's basis
    Quadric& q = t.quadric;
    double* c[] = {&q.A, &q.B, &q.C, &q.D, &q.E, &q.F, &q.G, &q.H, &q.I, &q.J};
    for (double* x : c) *x = 4.0 * u(rng);
    const int n = 1 + int(rng() % p.octaves);
    for (int i = 0; i < n; ++i) {
        Octave o;
        o.amplitude = u(rng);
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) o.M[r][k] = (r == k ? 8.0 : 2.0) * u(rng);
        o.offset = glm::dvec3(100.0 * u(rng), 100.0 * u(rng), 100.0 * u(rng));
        t.octaves.push_back(o);
    }
    std::vector<glm::dvec4> entries(p.clutSize());
    for (auto& e : entries) e = glm::dvec4(0.5 + 0.5 * u(rng), 0.5 + 0.5 * u(rng), 0.5 + 0.5 * u(rng), 0.5 + 0.5 * u(rng));
    t.clut = ColorMap(entries, rng() % 2 ? WrapMode::Clamp : WrapMode::Mod);
    const FilterKind kinds[] = {FilterKind::None, FilterKind::MipNearest, FilterKind::MipLinear, FilterKind::Sat};
    t.filter = kinds[rng() % 4];
    return t;
}

// Fragments: special values first, then random.
std::vector<FragmentRecord> specialAndRandomFragments(std::mt19937_64& rng, const Profile& p, int count) {
    std::vector<FragmentRecord> out;
    const double sMax = std::ldexp(1.0, p.coord.intBits - 1);       // largest |s| representable
    const double lsb = std::ldexp(1.0, -p.coord.fracBits);
    const double specials[] = {0.0, 1.0, -1.0, lsb, -lsb, 1.0 - lsb, -1.0 + lsb, 4095.0 / 4096.0, 7.0, -7.0,
                               sMax - lsb, -sMax, 0.5 * sMax, -0.5 * sMax, 1e9, -1e9};
    const double jac[] = {0.0, 1.0 / 256, 1e-6, 0.5, 4.0, -4.0, 1e3};
    for (double a : specials)
        for (double j : jac) out.push_back({{a, -a, a * 0.5}, {j, 0.0, 0.0}, {0.0, j, -j}});
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    while (int(out.size()) < count) {
        const double scale = std::ldexp(1.0, int(rng() % 12) - 2);  // 0.25 .. 512
        const double js = std::ldexp(1.0, -int(rng() % 14));        // 1 .. 1/8192
        out.push_back({{scale * u(rng), scale * u(rng), scale * u(rng)},
                       {js * u(rng), js * u(rng), js * u(rng)},
                       {js * u(rng), js * u(rng), js * u(rng)}});
    }
    return out;
}

TEST_P(EveryProfile, ConstrainedRandomWithStallsMatchesGolden) {
    const Profile p = profile(GetParam());
    const uint64_t seed = 20261122;
    std::printf("constrained random: profile %s, seed %llu\n", p.name.c_str(), (unsigned long long)seed);
    std::mt19937_64 rng(seed);
    SimOptions so;
    so.seed = seed;
    so.inputGapRate = 0.3;
    so.outputStallRate = 0.4;
    auto rtl = makeRtlModel(p.name, so);
    GoldenPipeline golden(p);
    Scoreboard board(p);
    size_t total = 0;
    for (int textureNo = 0; textureNo < 12; ++textureNo) {
        const Texture tex = randomTexture(rng, p);
        const TextureProgram prog = programTexture(p, tex);
        for (const auto& [a, d] : prog.writes) golden.write(a, d);
        rtl->write(prog.writes);
        const auto recs = specialAndRandomFragments(rng, p, 400);
        std::vector<FragmentFx> in;
        for (const auto& r : recs) in.push_back(quantizeFragment(p, uint32_t(total + in.size()), r.s, r.dsdx, r.dsdy));
        for (const auto& f : in) {
            UnitTrace tr;
            PixelFx px = golden.eval(f, &tr);
            board.expect(f, px, tr);
        }
        std::map<uint32_t, ProbeFx> probes;
        for (const auto& px : rtl->run(in, prog.activeOctaves, &probes)) board.observe(px, &probes[px.tag]);
        total += in.size();
    }
    board.finish();
    EXPECT_TRUE(board.passed()) << board.summary();
    EXPECT_EQ(board.checked(), total);
}

// The scoreboard catches a perturbed golden unit and names it as the first that differs.
TEST_P(EveryProfile, ScoreboardNamesAPerturbedUnit) {
    const Profile p = profile(GetParam());
    Scene scene = loadScene(sourceDir() + "/scenes/" + basisScene(p) + ".toml", 24, 24);
    for (Unit s : {Unit::Transform, Unit::Noise, Unit::Quadric, Unit::Accumulate, Unit::FilterWidth,
                    Unit::ClutFilter}) {
        SCOPED_TRACE(toString(s));
        auto rtl = makeRtlModel(p.name, {});
        HwRenderOptions ho;
        ho.fault = s;
        HwRenderResult r = renderHardware(scene, p, rtl.get(), ho);
        EXPECT_FALSE(r.passed);
        ASSERT_EQ(r.mismatches, size_t(r.fragments));  // the fault touches every pixel
        ASSERT_EQ(r.byUnit.size(), 1u) << r.scoreboard;
        EXPECT_EQ(r.byUnit.begin()->first, s) << r.scoreboard;
    }
}

// A texture whose noise basis is not the profile's is refused (not rendered with the
// profile's noise in its place), naming the scene file, line and field (or the texture, for
// the default basis).
TEST_P(EveryProfile, RefusesOtherBases) {
    const Profile p = profile(GetParam());
    const std::string path = sourceDir() + "/scenes/bases.toml";
    Scene scene = loadScene(path, 16, 16);
    int refused = 0, expected = 0;
    for (const Texture& tex : scene.textures) {
        const std::string why = hardwareUnsupported(p, tex);
        // A worley profile also refuses worley textures of another variant (bases.toml's are
        // the paper's exact search), naming the noise table's line.
        const bool otherVariant = tex.noise.basis == NoiseBasis::Worley && p.noise.basis == NoiseBasis::Worley &&
                                  (tex.noise.search != p.noise.search || tex.noise.cubes != WorleyCubes::Rom256);
        expected += tex.noise.basis != p.noise.basis || otherVariant;
        if (tex.noise.basis == p.noise.basis && !otherVariant) {
            EXPECT_EQ(why, "") << tex.name;
            continue;
        }
        if (otherVariant) {
            EXPECT_NE(why.find(path + ":"), std::string::npos) << why;
            EXPECT_NE(why.find("textures." + tex.name + ".noise.search/max_points/cubes: "), std::string::npos) << why;
            EXPECT_THROW(programTexture(p, tex), InputError);
            ++refused;
            continue;
        }
        if (tex.basisSource.empty()) {  // the default basis (rayshade): no line to name
            EXPECT_EQ(why.rfind("texture '" + tex.name + "': noise.basis: basis '", 0), 0u) << why;
        } else {
            EXPECT_NE(why.find(path + ":"), std::string::npos) << why;
            EXPECT_NE(why.find("textures." + tex.name + ".noise.basis: basis '"), std::string::npos) << why;
        }
        EXPECT_THROW(programTexture(p, tex), InputError);
        ++refused;
    }
    EXPECT_EQ(refused, expected);
    EXPECT_GE(refused, 6);  // the six worley textures at least
    auto rtl = makeRtlModel(p.name, {});
    EXPECT_THROW(renderHardware(scene, p, rtl.get()), InputError);
}

INSTANTIATE_TEST_SUITE_P(Profiles, EveryProfile, ::testing::ValuesIn(rtlProfiles()));

}  // namespace
}  // namespace pst
