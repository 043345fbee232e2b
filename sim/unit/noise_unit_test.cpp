// Unit test of units 1 and 2 (rtl/octave/pst_octave_transform.sv, rtl/noise/pst_noise.sv) against the
// golden model (model/golden/noise_fx.cpp): every output bit, special values first, then
// random vectors from a printed seed (PST_SEED=<n> replays). One executable per profile
// (PST_PROFILE_PATH, relative to the source tree), optionally with noise parameters overridden (PST_NOISE_OVERRIDES, the
// same -G overrides the verilated top was built with; see sim/unit/noise.cmake).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "Vpst_noise_unit_top.h"
#include "contract.h"
#include "fixed.h"
#include "verilated_port.h"
#include "noise_fx.h"
#include "profile.h"
#include "source_dir.h"
#include "verilated.h"

namespace pst {
namespace {

constexpr int kLB = contract::kLatticeBits;             // one lattice index
constexpr int kLatMask = (1 << contract::kLatticeBits) - 1;

// ---- generic port access (sim/verilated_port.h) -------------------------------------------
template <typename T>
void setField(T& port, int lsb, int width, uint64_t value) { port::set(port, lsb, width, value); }
template <typename T>
uint64_t getField(const T& port, int lsb, int width) { return port::get(port, lsb, width); }

// ---- profile (with the variant's overrides) -----------------------------------------------
Profile testProfile() {
    Profile p = loadProfile(sourceDir() + "/" PST_PROFILE_PATH);
#ifdef PST_NOISE_OVERRIDES
    std::stringstream ss(PST_NOISE_OVERRIDES);
    std::string item;
    while (std::getline(ss, item, ',')) {
        const auto eq = item.find('=');
        const std::string key = item.substr(0, eq);
        const int v = std::stoi(item.substr(eq + 1));
        const auto* name = std::find(std::begin(contract::kParamNames), std::end(contract::kParamNames), key);
        if (name == std::end(contract::kParamNames)) throw std::runtime_error("unknown override " + key);
        contract::setParam(p, contract::Param(name - std::begin(contract::kParamNames)), v);
    }
    p.noise = hardwareNoise(p);
#endif
    return p;
}

uint64_t seed() {
    if (const char* s = std::getenv("PST_SEED")) return std::strtoull(s, nullptr, 0);
    return std::random_device{}();
}

// One verilated model for the whole executable ($readmemh runs once).
class NoiseUnit : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        ctx_ = std::make_unique<VerilatedContext>();
        top_ = std::make_unique<Vpst_noise_unit_top>(ctx_.get());
    }
    static void TearDownTestSuite() {
        top_->final();
        top_.reset();
        ctx_.reset();
    }
    void SetUp() override {
        prof_ = testProfile();
        seed_ = seed();
        std::printf("[ noise_unit ] profile %s%s, seed %llu (PST_SEED=%llu replays)\n", prof_.name.c_str(),
#ifdef PST_NOISE_OVERRIDES
                    " + " PST_NOISE_OVERRIDES,
#else
                    "",
#endif
                    (unsigned long long)seed_, (unsigned long long)seed_);
        rng_.seed(seed_);
    }

    // ---- unit 1 ----
    struct OtVector {
        int64_t s[3], M[9], o[3];
    };
    // Drives the transform, compares lat and frac with the golden; returns true on a match and
    // hands back the golden outputs.
    bool checkTransform(const OtVector& v, int lat[3], int64_t frac[3]) {
        const int CW = prof_.coord.width(), MW = prof_.matrix.width(), OW = prof_.offset.width();
        const int LF = prof_.noiseLatticeFrac;
        for (int k = 0; k < 3; ++k) setField(top_->ot_s_i, k * CW, CW, fx::wrapUnsigned(v.s[k], CW));
        for (int k = 0; k < 9; ++k) setField(top_->ot_m_i, k * MW, MW, fx::wrapUnsigned(v.M[k], MW));
        for (int k = 0; k < 3; ++k) setField(top_->ot_o_i, k * OW, OW, fx::wrapUnsigned(v.o[k], OW));
        top_->eval();
        octaveTransformFx(prof_, v.s, v.M, v.o, lat, frac);
        ++vectors_;
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
            const uint64_t rl = getField(top_->ot_lat_o, kLB * k, kLB);
            const uint64_t rf = getField(top_->ot_frac_o, LF * k, LF);
            if (rl != uint64_t(lat[k]) || rf != uint64_t(frac[k])) ok = false;
        }
        if (!ok && ++mismatches_ <= 10) {
            std::ostringstream os;
            os << "octave transform mismatch: s";
            for (auto x : v.s) os << " " << x;
            os << " M";
            for (auto x : v.M) os << " " << x;
            os << " o";
            for (auto x : v.o) os << " " << x;
            for (int k = 0; k < 3; ++k)
                os << "\n  axis " << k << ": rtl lat " << getField(top_->ot_lat_o, kLB * k, kLB) << " frac "
                   << getField(top_->ot_frac_o, LF * k, LF) << ", golden lat " << lat[k] << " frac " << frac[k];
            ADD_FAILURE() << os.str();
        }
        return ok;
    }

    // ---- unit 2 ----
    bool checkNoise(const int lat[3], const int64_t frac[3]) {
        const int LF = prof_.noiseLatticeFrac, OF = prof_.noiseOutFrac;
        const int NW = contract::kNoiseIntBits + OF, NGW = contract::kNoiseGradIntBits + OF;
        for (int k = 0; k < 3; ++k) {
            setField(top_->nz_lat_i, kLB * k, kLB, uint64_t(lat[k]));
            setField(top_->nz_frac_i, LF * k, LF, uint64_t(frac[k]));
        }
        // NoiseSteps > 1: steps 0..S-2 stored on a clock edge each, the result live at S-1.
        top_->rst_ni = 1;
        top_->nz_adv_i = 1;
        for (int step = 0; step + 1 < prof_.noiseSteps; ++step) {
            top_->nz_step_i = step;
            top_->eval();
            top_->clk_i = 1;
            top_->eval();
            top_->clk_i = 0;
        }
        top_->nz_adv_i = 0;
        top_->nz_step_i = prof_.noiseSteps - 1;
        top_->eval();
        int64_t n, g[3];
        NoiseFxTrace tr;
        noiseFx(prof_, lat, frac, &n, g, &tr);
        ++vectors_;
        const uint64_t rn = getField(top_->nz_n_o, 0, NW);
        uint64_t rg[3];
        bool ok = rn == fx::wrapUnsigned(n, NW);
        for (int k = 0; k < 3; ++k) {
            rg[k] = getField(top_->nz_grad_o, k * (NGW), NGW);
            ok = ok && rg[k] == fx::wrapUnsigned(g[k], NGW);
        }
        if (!ok && ++mismatches_ <= 10) {
            std::ostringstream os;
            os << "noise mismatch: lat " << lat[0] << " " << lat[1] << " " << lat[2] << " frac " << frac[0] << " "
               << frac[1] << " " << frac[2] << "\n  rtl n " << fx::wrapSigned(rn, NW) << " grad";
            for (int k = 0; k < 3; ++k) os << " " << fx::wrapSigned(rg[k], NGW);
            os << "\n  golden n " << n << " grad " << g[0] << " " << g[1] << " " << g[2] << "\n  golden m";
            for (int c = 0; c < 8; ++c) os << " " << tr.m[c];
            os << " s " << tr.s[0] << " " << tr.s[1] << " " << tr.s[2] << " ds " << tr.ds[0] << " " << tr.ds[1]
               << " " << tr.ds[2] << "\n  golden root node " << tr.node[6][0] << " " << tr.node[6][1] << " "
               << tr.node[6][2] << " " << tr.node[6][3];
            ADD_FAILURE() << os.str();
        }
        return ok;
    }

    void report(const char* what) {
        std::printf("[ noise_unit ] %s: %llu vectors, %llu mismatches\n", what, (unsigned long long)vectors_,
                    (unsigned long long)mismatches_);
        EXPECT_EQ(mismatches_, 0u);
    }

    int64_t randomOf(const FixedFormat& f) { return fx::wrapSigned(int64_t(rng_()), f.width()); }
    int64_t randomFrac() { return int64_t(rng_() & ((uint64_t(1) << prof_.noiseLatticeFrac) - 1)); }

    static std::unique_ptr<VerilatedContext> ctx_;
    static std::unique_ptr<Vpst_noise_unit_top> top_;
    Profile prof_;
    uint64_t seed_ = 0;
    std::mt19937_64 rng_;
    uint64_t vectors_ = 0, mismatches_ = 0;
};

std::unique_ptr<VerilatedContext> NoiseUnit::ctx_;
std::unique_ptr<Vpst_noise_unit_top> NoiseUnit::top_;

TEST_F(NoiseUnit, OctaveTransformSpecialValues) {
    const FixedFormat cf = prof_.coord, mf = prof_.matrix, of = prof_.offset;
    const std::vector<int64_t> sv = {0, 1, -1, fx::maxSigned(cf.width()), fx::minSigned(cf.width()),
                                     int64_t(1) << cf.fracBits, -(int64_t(1) << cf.fracBits)};
    const std::vector<int64_t> mv = {0, 1, -1, fx::maxSigned(mf.width()), fx::minSigned(mf.width()),
                                     int64_t(1) << mf.fracBits};
    const std::vector<int64_t> ov = {0, -1, fx::maxSigned(of.width()), fx::minSigned(of.width()),
                                     int64_t(1) << of.fracBits};
    int lat[3];
    int64_t frac[3];
    for (int64_t s : sv)
        for (int64_t m : mv)
            for (int64_t o : ov) {
                // Same value everywhere, and a mixed pattern (M rows differ, s and o by axis).
                OtVector a;
                for (auto& x : a.s) x = s;
                for (auto& x : a.M) x = m;
                for (auto& x : a.o) x = o;
                checkTransform(a, lat, frac);
                OtVector b;
                for (int k = 0; k < 3; ++k) {
                    b.s[k] = sv[(k + size_t(s & 3)) % sv.size()];
                    b.o[k] = ov[(k + 1) % ov.size()];
                }
                for (int k = 0; k < 9; ++k) b.M[k] = k % 4 == 0 ? m : mv[size_t(k) % mv.size()];
                b.o[0] = o;
                b.s[2] = s;
                checkTransform(b, lat, frac);
            }
    report("octave transform special values");
}

TEST_F(NoiseUnit, OctaveTransformRandom) {
    int lat[3];
    int64_t frac[3];
    std::uniform_real_distribution<double> p(-50.0, 50.0), freq(-4.0, 4.0), phase(-100.0, 100.0);
    for (int it = 0; it < 30000; ++it) {
        OtVector v;
        if (it % 2 == 0) {  // any bit pattern
            for (auto& x : v.s) x = randomOf(prof_.coord);
            for (auto& x : v.M) x = randomOf(prof_.matrix);
            for (auto& x : v.o) x = randomOf(prof_.offset);
        } else {  // texture-like values
            for (auto& x : v.s) x = fx::quantize(p(rng_), prof_.coord.intBits, prof_.coord.fracBits);
            for (auto& x : v.M) x = fx::quantize(freq(rng_), prof_.matrix.intBits, prof_.matrix.fracBits);
            for (auto& x : v.o) x = fx::quantize(phase(rng_), prof_.offset.intBits, prof_.offset.fracBits);
        }
        checkTransform(v, lat, frac);
    }
    report("octave transform random");
}

TEST_F(NoiseUnit, NoiseSpecialValues) {
    const int LF = prof_.noiseLatticeFrac;
    const int64_t maxU = (int64_t(1) << LF) - 1;
    // Lattice: 0, the wrap 4095 -> 0, the perm256 wrap 255 -> 256, Rayshade's origin 576 (and
    // perlin256's X = 0), perlin256's wrap X = 255 -> 0 at L = 319 -> 320 (X = (L - 64) mod 256).
    const std::vector<int> lats = {0, 4095, 255, 256, 576, 1, 319, 63};
    // Fractions: u = 0 (lattice plane), u = max, 1 LSB, one half, max - 1, the SCURVE
    // derivative's maximum neighbourhood.
    std::vector<int64_t> fracs = {0, maxU, 1, int64_t(1) << (LF - 1), maxU - 1};
    if (LF >= 2) fracs.push_back((int64_t(1) << (LF - 1)) + 1);
    for (int lx : lats)
        for (int ly : lats)
            for (int lz : lats)
                for (size_t f = 0; f < fracs.size() * fracs.size(); ++f) {
                    const int lat[3] = {lx, ly, lz};
                    const int64_t frac[3] = {fracs[f % fracs.size()], fracs[f / fracs.size()],
                                             fracs[(f + lx + ly) % fracs.size()]};
                    checkNoise(lat, frac);
                }
    // Every fraction pattern of all three axes at two lattice points.
    for (int l : {0, 4095})
        for (int64_t fx0 : fracs)
            for (int64_t fy : fracs)
                for (int64_t fz : fracs) {
                    const int lat[3] = {l, 4095 - l, l};
                    const int64_t frac[3] = {fx0, fy, fz};
                    checkNoise(lat, frac);
                }
    report("noise special values");
}

TEST_F(NoiseUnit, NoiseRandom) {
    for (int it = 0; it < 30000; ++it) {
        const int lat[3] = {int(rng_() & kLatMask), int(rng_() & kLatMask), int(rng_() & kLatMask)};
        const int64_t frac[3] = {randomFrac(), randomFrac(), randomFrac()};
        checkNoise(lat, frac);
    }
    report("noise random");
}

// Unit 1 into unit 2 as in the pipeline: texture-like s, M, o; the noise unit gets the
// transform outputs (golden values, checked equal to the RTL transform first).
TEST_F(NoiseUnit, TransformThenNoise) {
    std::uniform_real_distribution<double> p(-50.0, 50.0), freq(-4.0, 4.0), phase(-100.0, 100.0);
    for (int it = 0; it < 20000; ++it) {
        OtVector v;
        for (auto& x : v.s) x = fx::quantize(p(rng_), prof_.coord.intBits, prof_.coord.fracBits);
        for (auto& x : v.M) x = fx::quantize(freq(rng_), prof_.matrix.intBits, prof_.matrix.fracBits);
        for (auto& x : v.o) x = fx::quantize(phase(rng_), prof_.offset.intBits, prof_.offset.fracBits);
        int lat[3];
        int64_t frac[3];
        checkTransform(v, lat, frac);
        checkNoise(lat, frac);
    }
    report("transform then noise");
}

}  // namespace
}  // namespace pst
