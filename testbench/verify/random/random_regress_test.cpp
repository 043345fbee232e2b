// The constrained-random regression: its generators reach what they promise (every filter kind
// and wrap, 0..Octaves octaves, saturated f, grad and W, lattice planes, zero and extreme
// Jacobians), a seed replays, and a perturbed golden unit is caught at the right fragment,
// also when replayed alone.
#include "random_regress.h"

#include <set>

#include <gtest/gtest.h>

#include "driver.h"
#include "fixed.h"
#include "input_error.h"
#include "rtl_model.h"
#include "source_dir.h"

namespace pst {
namespace {

Profile profile(const std::string& name) { return loadProfile(rtlProfilePath(name)); }

TEST(RandomStream, SameSeedSameStreamAndRangesHold) {
    RandomStream a(42), b(42), c(43);
    bool differs = false;
    for (int i = 0; i < 1000; ++i) {
        const uint64_t x = a.next();
        EXPECT_EQ(x, b.next());
        differs = differs || x != c.next();
        const int64_t v = a.range(-3, 5);
        b.range(-3, 5);
        EXPECT_GE(v, -3);
        EXPECT_LE(v, 5);
        const double u = a.uniform();
        b.uniform();
        EXPECT_GE(u, 0.0);
        EXPECT_LT(u, 1.0);
    }
    EXPECT_TRUE(differs);
}

TEST(RandomRegress, TexturesReachEveryKindWrapOctaveCountAndRegisterExtreme) {
    for (const std::string& name : rtlProfiles()) {
        SCOPED_TRACE(name);
        const Profile p = profile(name);
        RandomStream r(7);
        std::set<int> kinds, wraps, octaves;
        bool quadricMax = false, quadricMin = false, dropped = false;
        for (int i = 0; i < 500; ++i) {
            const Texture t = randomTexture(r, p);
            const TextureProgram prog = programTexture(p, t);
            kinds.insert(prog.filterKind);
            wraps.insert(int(t.clut.wrap()));
            octaves.insert(prog.activeOctaves);
            dropped = dropped || prog.droppedOctaves > 0;
            for (const auto& [a, d] : prog.writes)
                if (a >= 0x10 && a < 0x1a) {
                    const int64_t v = fx::wrapSigned(d, p.quadric.width());
                    quadricMax = quadricMax || v == fx::maxSigned(p.quadric.width());
                    quadricMin = quadricMin || v == fx::minSigned(p.quadric.width());
                }
        }
        EXPECT_EQ(kinds.size(), 4u);
        EXPECT_EQ(wraps.size(), 2u);
        EXPECT_EQ(int(octaves.size()), p.octaves + 1);  // 0..Octaves
        EXPECT_TRUE(dropped);
        EXPECT_TRUE(quadricMax && quadricMin);
    }
}

TEST(RandomRegress, FragmentsAndGoldenOutputsReachTheCorners) {
    for (const std::string& name : rtlProfiles()) {
        SCOPED_TRACE(name);
        const Profile p = profile(name);
        RandomStream r(11);
        const int cw = p.coord.width(), jw = p.jacobian.width(), fw = p.f.width(), gw = p.grad.width();
        const int64_t wmax = fx::maxUnsigned(p.widthBits());
        bool sMax = false, sMin = false, lattice = false, jZero = false, jMax = false, jMin = false;
        int fSat = 0, fFree = 0, gSat = 0, wSat = 0, wZero = 0, wMid = 0;
        for (int batch = 0; batch < 60; ++batch) {
            const Texture t = randomTexture(r, p);
            GoldenPipeline golden(p);
            for (const auto& [a, d] : programTexture(p, t).writes) golden.write(a, d);
            for (const FragmentFx& f : randomFragments(r, p, 0, 200)) {
                bool zero = true;
                for (int k = 0; k < 3; ++k) {
                    sMax = sMax || f.s[k] == fx::maxSigned(cw);
                    sMin = sMin || f.s[k] == fx::minSigned(cw);
                    lattice = lattice || (f.s[k] != 0 && f.s[k] % (int64_t(1) << p.coord.fracBits) == 0);
                }
                for (int k = 0; k < 6; ++k) {
                    zero = zero && f.j[k] == 0;
                    jMax = jMax || f.j[k] == fx::maxSigned(jw);
                    jMin = jMin || f.j[k] == fx::minSigned(jw);
                }
                jZero = jZero || zero;
                const PixelFx px = golden.eval(f);
                const bool fs = px.f == fx::maxSigned(fw) || px.f == fx::minSigned(fw);
                (fs ? fSat : fFree)++;
                for (int k = 0; k < 3; ++k) gSat += px.grad[k] == fx::maxSigned(gw) || px.grad[k] == fx::minSigned(gw);
                wSat += px.w == wmax;
                wZero += px.w == 0;
                wMid += px.w > 0 && px.w < wmax;
            }
        }
        EXPECT_TRUE(sMax && sMin && lattice && jZero && jMax && jMin);
        // Saturated and unsaturated results both occur, in a good share each.
        EXPECT_GT(fSat, 200);
        EXPECT_GT(fFree, 2000);
        EXPECT_GT(gSat, 200);
        EXPECT_GT(wSat, 200);
        EXPECT_GT(wZero, 200);
        EXPECT_GT(wMid, 1000);
    }
}

// The width cap (issue 44 part 2) end to end through the driver and the golden model: on a profile
// with the unit (filter.width_cap = "on") the driver writes wcap = floor(widthCapOf N 2^WidthFrac)
// for a noise-only texture that asks for it (all ones when it does not, or when its quadric
// varies), and the golden W is min(W, wcap): a minified pixel's W is the cap, a magnified one's
// unchanged. A profile without the unit refuses the texture and ignores the register.
TEST(RandomRegress, WidthCapThroughDriverAndGolden) {
    const Profile p = loadNamedProfile(sourceDir() + "/sim/test_profiles/reduced_worley.toml", sourceDir());
    ASSERT_TRUE(p.widthCap());
    const int64_t wmax = fx::maxUnsigned(p.widthBits());
    Texture tex;
    tex.name = "t";
    tex.noise = p.noise;
    tex.noise.coef = {1.0, 0.0, 0.0, 0.0};
    tex.clut = ColorMap(std::vector<glm::dvec4>(size_t(p.clutSize()), glm::dvec4(0.5)), WrapMode::Mod);
    tex.filter = FilterKind::Sat;
    for (double a : {0.5, 0.25}) {
        Octave o;
        o.amplitude = a;
        o.M = glm::dmat3(3.0);
        tex.octaves.push_back(o);
    }
    auto wcapOf = [&](const Texture& t) {
        int64_t v = -2;
        for (const auto& [addr, d] : programTexture(p, t).writes)
            if (addr == contract::kRegWcap) v = int64_t(d);
        return v;
    };
    EXPECT_EQ(wcapOf(tex), wmax);   // width_cap off: all ones
    tex.widthCap = true;
    const double capF = widthCapOf(tex);
    const int64_t wcap = int64_t(std::floor(capF * p.clutSize() * std::exp2(p.widthFrac)));
    EXPECT_GT(wcap, 0);
    EXPECT_LT(wcap, wmax);
    EXPECT_EQ(wcapOf(tex), wcap);
    EXPECT_EQ(widthCapRegister(p, tex, 2), wcap);
    EXPECT_LT(widthCapRegister(p, tex, 1), wcap);   // the octaves the hardware holds
    Texture quad = tex;
    quad.quadric.D = 0.5;   // a varying quadric: no cap
    EXPECT_EQ(wcapOf(quad), wmax);
    EXPECT_NE(programTexture(p, quad).notes.find("width cap: none (the quadric varies)"), std::string::npos);

    GoldenPipeline capped(p), open(p);
    for (const auto& [addr, d] : programTexture(p, tex).writes) capped.write(addr, d);
    Texture off = tex;
    off.widthCap = false;
    for (const auto& [addr, d] : programTexture(p, off).writes) open.write(addr, d);
    bool clipped = false, kept = false;
    for (int k = 0; k < 200; ++k) {
        const double scale = std::exp2(-12.0 + 0.1 * k);   // magnified to minified
        const glm::dvec3 s(0.37 + 0.01 * k, 0.21, 0.13);
        const FragmentFx f = quantizeFragment(p, uint32_t(k), s, glm::dvec3(scale, 0.3 * scale, 0),
                                              glm::dvec3(0, scale, 0.2 * scale));
        const PixelFx a = open.eval(f), b = capped.eval(f);
        EXPECT_EQ(b.w, std::min(a.w, wcap));
        EXPECT_EQ(b.f, a.f);
        clipped = clipped || a.w > wcap;
        kept = kept || (a.w > 0 && a.w < wcap);
    }
    EXPECT_TRUE(clipped);
    EXPECT_TRUE(kept);

    // Without the unit: refused, and the register is not kept.
    const Profile r = loadNamedProfile("reduced", sourceDir());
    ASSERT_FALSE(r.widthCap());
    Texture rt = tex;
    rt.noise = r.noise;
    EXPECT_THROW(programTexture(r, rt), InputError);
    EXPECT_NE(hardwareUnsupported(r, rt).find("has no width-cap unit"), std::string::npos);
    rt.widthCap = false;
    GoldenPipeline g(r), h(r);
    for (const auto& [addr, d] : programTexture(r, rt).writes) {
        EXPECT_NE(addr, contract::kRegWcap);
        g.write(addr, d);
        h.write(addr, d);
    }
    h.write(contract::kRegWcap, 3);
    const FragmentFx f = quantizeFragment(r, 1, glm::dvec3(0.3), glm::dvec3(100, 0, 0), glm::dvec3(0, 100, 0));
    EXPECT_EQ(g.eval(f).w, h.eval(f).w);
    EXPECT_GT(h.eval(f).w, 3);
}

TEST(RandomRegress, SegmentStartsAreConsistent) {
    RandomRegressOptions o;
    o.seed = 5;
    uint64_t g0 = 99, g1 = 99;
    EXPECT_EQ(segmentStart(o, 0, &g0), 0u);
    EXPECT_EQ(g0, 0u);
    const uint64_t s = segmentStart(o, 100000, &g1);
    EXPECT_LE(s, 100000u);
    EXPECT_GT(g1, 0u);
    // The segment before ends where this one starts.
    EXPECT_LT(segmentStart(o, s - 1), s);
    EXPECT_EQ(segmentStart(o, s), s);
    // segmentStarts lists the same boundaries, from the segment holding `from` on.
    o.from = 100000;
    o.fragments = 50000;
    const std::vector<uint64_t> starts = segmentStarts(o);
    ASSERT_GE(starts.size(), 2u);
    EXPECT_EQ(starts.front(), s);
    for (size_t i = 1; i < starts.size(); ++i) {
        EXPECT_EQ(segmentStart(o, starts[i]), starts[i]);
        EXPECT_EQ(segmentStart(o, starts[i] - 1), starts[i - 1]);
    }
    EXPECT_LT(starts.back(), 150000u);
    EXPECT_GE(segmentStart(o, 149999), starts.back());
}

// The regression can fail: a perturbed golden unit from fragment X on is reported at X, and
// replaying from X alone reports X again.
TEST(RandomRegress, PerturbedGoldenIsCaughtAtItsFragmentAndReplays) {
    const std::string name = rtlProfiles().back();
    const Profile p = profile(name);
    RandomRegressOptions o;
    o.seed = 3;
    o.maxBatch = 300;
    o.fragments = 6000;
    const RandomRegressResult clean = runRandomRegress(p, name, o);
    EXPECT_TRUE(clean.passed) << clean.report;
    EXPECT_EQ(clean.fragments, 6000u);
    EXPECT_GT(clean.textures, 10u);

    o.fault = Unit::Accumulate;
    o.faultFrom = 4321;
    const RandomRegressResult bad = runRandomRegress(p, name, o);
    EXPECT_FALSE(bad.passed);
    EXPECT_EQ(bad.firstBad, 4321u) << bad.report;

    o.from = 4321;
    o.fragments = 1;
    const RandomRegressResult replay = runRandomRegress(p, name, o);
    EXPECT_FALSE(replay.passed);
    EXPECT_EQ(replay.firstBad, 4321u);
    EXPECT_LE(replay.firstFragment, 4321u);
    EXPECT_LE(replay.fragments, 4321u - replay.firstFragment + 1);
}

// A failed RTL assertion is a failed run, not a crash: the testbench writes a register while
// the pipeline is busy (a protocol violation), Verilator's $error fires in pst_top's checker,
// the run stops at that segment with the fragment named, and the replay fires it again.
// On a profile verilated with its assertions (every test profile is).
TEST(RandomRegress, FailedAssertionIsAFailedRunThatReplays) {
    const std::vector<std::string> asserted = rtlAssertedProfiles();
    ASSERT_FALSE(asserted.empty()) << "no profile of this build is verilated with assertions";
    const std::string name = asserted.back();
    const Profile p = profile(name);
    RandomRegressOptions o;
    o.seed = 3;
    o.maxBatch = 300;
    o.fragments = 6000;
    o.injectAssert = 4321;
    testing::internal::CaptureStdout();
    const RandomRegressResult bad = runRandomRegress(p, name, o);
    const std::string printed = testing::internal::GetCapturedStdout();
    EXPECT_FALSE(bad.passed);
    EXPECT_TRUE(bad.assertion);
    EXPECT_NE(printed.find("RegWriteOnlyWhenIdle"), std::string::npos) << printed;
    // Named by the oldest fragment in flight: at or before 4321, in its segment; the run stopped there.
    EXPECT_LE(bad.firstBad, 4321u);
    EXPECT_GE(bad.firstBad, segmentStart(o, 4321));
    EXPECT_LT(bad.fragments, 6000u);
    EXPECT_GT(bad.replayFragments, 4321u - bad.firstBad);
    EXPECT_NE(bad.report.find("RTL assertion at cycle " + std::to_string(bad.assertionCycle)), std::string::npos)
        << bad.report;

    o.from = bad.firstBad;
    o.fragments = bad.replayFragments;
    testing::internal::CaptureStdout();
    const RandomRegressResult replay = runRandomRegress(p, name, o);
    testing::internal::GetCapturedStdout();
    EXPECT_TRUE(replay.assertion);
    EXPECT_EQ(replay.firstBad, bad.firstBad);
    EXPECT_EQ(replay.assertionCycle, bad.assertionCycle);

    // The same segment without the protocol violation passes.
    o.injectAssert = UINT64_MAX;
    const RandomRegressResult clean = runRandomRegress(p, name, o);
    EXPECT_TRUE(clean.passed) << clean.report;
    EXPECT_FALSE(clean.assertion);
}

}  // namespace
}  // namespace pst
