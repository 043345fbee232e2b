// Unit test of the arithmetic units against the golden model, one verilated top per profile
// (sim/unit/pst_arith_unit_top.sv): pst_quadric vs quadricFx, pst_octave_term vs
// octaveTermFx, pst_filter_width (the profile's norm and all three) vs filterWidthFx,
// pst_isqrt vs isqrtFx and floor(sqrt). Every output bit must match.
//
// Vectors per module: special values first (every input at its format's min or max, in all
// combinations; zeros; constructed values that land exactly on each saturation boundary;
// perfect squares and their neighbours), then random vectors from a printed seed (PST_SEED
// replays a run): log-uniform magnitudes, so every range of every output is reached, mixed
// with uniform full-range values and format extremes. The first mismatches are printed with
// their inputs.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <verilated.h>

#include "Vpst_arith_unit_top.h"
#include "arith_fx.h"
#include "contract.h"
#include "fixed.h"
#include "verilated_port.h"
#include "profile.h"
#include "unit/unit_seed.h"

namespace {

using pst::Profile;
using pst::fx::i128;
namespace fx = pst::fx;

// --- Port access (sim/verilated_port.h) ------------------------------------------------------
template <typename T>
void setBits(T& p, int lsb, int width, uint64_t v) { pst::port::set(p, lsb, width, v); }
template <typename T>
void clearPort(T& p) { p = 0; }
template <std::size_t N>
void clearPort(VlWide<N>& p) {
    for (std::size_t i = 0; i < N; ++i) p[i] = 0;
}
template <typename T>
uint64_t getBits(const T& p, int lsb, int width) { return pst::port::get(p, lsb, width); }
template <typename T>
int64_t getSigned(const T& p, int lsb, int width) { return pst::port::getSigned(p, lsb, width); }

// --- Profile, seed, random values ------------------------------------------------------------
using pst::unit::prof;
uint64_t seed() { return pst::unit::seed("arith_unit"); }

struct Rng {
    std::mt19937_64 g;
    explicit Rng(uint64_t salt) : g(seed() ^ (salt * 0x9e3779b97f4a7c15ull)) {}
    uint64_t bits(int n) { return n >= 64 ? g() : g() & ((uint64_t(1) << n) - 1); }
    int64_t range(int64_t lo, int64_t hi) {  // uniform in [lo, hi]
        return lo + int64_t(g() % uint64_t(hi - lo + 1));
    }
    // A signed `width`-bit value: extremes, uniform, or log-uniform magnitude (the usual case).
    int64_t sval(int width) {
        const int64_t lo = fx::minSigned(width), hi = fx::maxSigned(width);
        switch (g() % 16) {
        case 0: {
            const int64_t sp[] = {lo, hi, 0, -1, 1, lo + 1, hi - 1};
            return sp[g() % 7];
        }
        case 1:
        case 2: return fx::wrapSigned(i128(bits(width)), width);
        default: {
            const int b = int(g() % uint64_t(width));  // magnitude in [2^(b-1), 2^b)
            int64_t m = b == 0 ? 0 : int64_t((uint64_t(1) << (b - 1)) | bits(b - 1));
            return (g() & 1) ? -m : m;
        }
        }
    }
    // A signed value of at most `maxBits` magnitude bits (log-uniform), for products aimed at
    // an output range.
    int64_t svalBits(int width, int maxBits) {
        maxBits = std::max(0, std::min(maxBits, width - 1));
        const int b = int(g() % uint64_t(maxBits + 1));
        const int64_t m = b == 0 ? 0 : int64_t((uint64_t(1) << (b - 1)) | bits(b - 1));
        return (g() & 1) ? -m : m;
    }
    uint64_t uval(int width) {  // unsigned `width`-bit, log-uniform or uniform
        if (g() % 4 == 0) return bits(width);
        const int b = int(g() % uint64_t(width + 1));
        return b == 0 ? 0 : (uint64_t(1) << (b - 1)) | bits(b - 1);
    }
};

i128 floorDiv(i128 a, i128 b) {  // b > 0
    i128 q = a / b;
    if ((a % b) != 0 && a < 0) --q;
    return q;
}
bool fits(i128 v, int width) { return v >= fx::minSigned(width) && v <= fx::maxSigned(width); }

// --- Mismatch bookkeeping ----------------------------------------------------------------------
struct Tally {
    std::string what;
    long vectors = 0, mismatches = 0;
    void check(bool ok, const std::function<std::string()>& describe) {
        ++vectors;
        if (ok) return;
        if (++mismatches <= 8) ADD_FAILURE() << what << " mismatch #" << mismatches << ":\n" << describe();
    }
    ~Tally() {
        std::printf("arith_unit[%s]: %-34s %8ld vectors, %ld mismatches\n", prof().name.c_str(), what.c_str(),
                    vectors, mismatches);
    }
};

std::string list(const int64_t* v, int n) {
    std::ostringstream os;
    for (int i = 0; i < n; ++i) os << (i ? " " : "") << v[i];
    return os.str();
}

// --- The verilated top -------------------------------------------------------------------------
class ArithUnit : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        ctx_ = std::make_unique<VerilatedContext>();
        // An RTL assertion ($error) is counted as a mismatch of the vector that raised it
        // (see eval()) instead of stopping the process.
        ctx_->fatalOnError(false);
        top_ = std::make_unique<Vpst_arith_unit_top>(ctx_.get());
        (void)seed();
    }
    // Each test starts from all-zero inputs, so an RTL assertion is charged to the module under test.
    void SetUp() override {
        Vpst_arith_unit_top& d = *top_;
        clearPort(d.quad_s_i), clearPort(d.quad_coef_i);
        clearPort(d.term_n_i), clearPort(d.term_g_i), clearPort(d.term_a_i), clearPort(d.term_gm_i);
        clearPort(d.fw_grad_i), clearPort(d.fw_j_i), clearPort(d.sqrt_x_i), clearPort(d.fs_x_i);
        // The serial variants: out of reset, at step 0, clock low.
        d.clk_i = 0, d.rst_ni = 1, d.ser_step_i = 0, d.ser_adv_i = 0, d.quad_ser_step_i = 0, d.quad_ser_step_next_i = 0, d.quad_ser_adv_i = 0, d.quad_fold_en_i = 0, d.quad_fold_first_i = 0;
        ASSERT_TRUE(eval()) << "an RTL assertion fired on all-zero inputs";
    }
    static void TearDownTestSuite() {
        top_->final();
        top_.reset();
        ctx_.reset();
    }

    // Evaluates the top; false if an RTL assertion fired.
    static bool eval() {
        top_->eval();
        if (!ctx_->gotError()) return true;
        ctx_->gotError(false);
        return false;
    }

    const Profile& P = prof();
    const int CW = P.coord.width(), QW = P.quadric.width(), FW = P.f.width(), GW = P.grad.width();
    const int NW = pst::contract::kNoiseIntBits + P.noiseOutFrac, NGW = pst::contract::kNoiseGradIntBits + P.noiseOutFrac, AW = P.amplitude.width();
    const int GMW = P.gradMatrix.width(), JW = P.jacobian.width(), WW = P.widthBits();
    const int SqW = 2 * WW + 1;

    // One clock edge (the serial variants' partial-sum registers).
    static bool tick() {
        top_->clk_i = 1;
        const bool ok = eval();
        top_->clk_i = 0;
        return eval() && ok;
    }
    // Steps a serial variant (step and adv: its ports) through steps 0..last-1 (stored on a
    // clock edge each) to `last` on the inputs already driven: its result is then live
    // (combinational). With hold, step `last` is stored too and the step moves to last + 1,
    // where the result comes from the registers alone. An idle cycle comes first, whatever
    // step the previous vector left. A unit that decodes its step one cycle ahead (the serial
    // quadric) also gets the step after each clock edge (next). Returns false if an assertion
    // fired.
    template <typename S>
    static bool runSerial(S& step, uint8_t& adv, int last, bool hold, S* next = nullptr) {
        bool ok = true;
        auto setNext = [&](int k) {
            if (next) *next = S(k);
        };
        adv = 0;
        setNext(0);
        ok = eval() && ok;
        ok = tick() && ok;
        adv = 1;
        for (int k = 0; k < last; ++k) {
            step = S(k);
            setNext(k + 1);
            ok = eval() && ok;
            ok = tick() && ok;
        }
        step = S(last);
        ok = eval() && ok;
        if (hold) {
            setNext(last + 1);
            ok = eval() && ok;
            ok = tick() && ok;
            step = S(last + 1);
            adv = 0;
            ok = eval() && ok;
        }
        adv = 0;
        return ok;
    }

    // A serial unit's step count: the first step at which its done port rises (step port left
    // at 0 afterwards).
    template <typename S, typename D>
    static int stepsUntilDone(S& step, const D& done) {
        int n = 0;
        for (int k = 0; k < 32 && n == 0; ++k) {
            step = S(k);
            eval();
            if (done) n = k + 1;
        }
        step = 0;
        eval();
        return n;
    }
    // The serial quadric's, the serial filter width's (6, more for the euclidean norm), found once.
    static int quadricSteps() {
        static const int n = stepsUntilDone(top_->quad_ser_step_i, top_->quad_ser_done_o);
        return n;
    }
    static int widthSteps(bool euclid = false) {
        static const int n[2] = {stepsUntilDone(top_->ser_step_i, top_->fw_ser_done_o),
                                 stepsUntilDone(top_->ser_step_i, top_->fw_ser_euclid_done_o)};
        return n[euclid ? 1 : 0];
    }

    // Quadric: drive, evaluate, compare with the golden model.
    int64_t quadric(Tally& t, const int64_t s[3], const int64_t coef[10]) {  // returns golden q
        Vpst_arith_unit_top& d = *top_;
        for (int k = 0; k < 3; ++k) setBits(d.quad_s_i, k * CW, CW, uint64_t(s[k]));
        for (int k = 0; k < 10; ++k) setBits(d.quad_coef_i, k * QW, QW, uint64_t(coef[k]));
        const bool assertOk = eval();
        int64_t q, gq[3];
        pst::quadricFx(P, s, coef, &q, gq);
        const int64_t rq = getSigned(d.quad_q_o, 0, FW);
        int64_t rg[3];
        for (int k = 0; k < 3; ++k) rg[k] = getSigned(d.quad_gradq_o, k * GW, GW);
        // The serial quadric: live at its last step, then held (from its registers) after it.
        int64_t sq[2], sg[2][3];
        bool serialOk = true;
        for (int h = 0; h < 2; ++h) {
            serialOk = runSerial(d.quad_ser_step_i, d.quad_ser_adv_i, quadricSteps() - 1, h == 1,
                                 &d.quad_ser_step_next_i) && serialOk;
            sq[h] = getSigned(d.quad_ser_q_o, 0, FW);
            for (int k = 0; k < 3; ++k) sg[h][k] = getSigned(d.quad_ser_gradq_o, k * GW, GW);
        }
        bool serialMatch = true;
        for (int h = 0; h < 2; ++h)
            serialMatch = serialMatch && sq[h] == q && sg[h][0] == gq[0] && sg[h][1] == gq[1] && sg[h][2] == gq[2];
        // The folded quadric: rows 0 and 1 held at an enabled edge with first, row 2 live
        // after it; on every other vector a stalled edge (en low, first high) with other
        // inputs between them must leave the held rows alone.
        d.quad_ser_adv_i = 0, d.ser_adv_i = 0;
        d.quad_fold_en_i = 1, d.quad_fold_first_i = 1;
        bool foldOk = tick();
        if (++foldVectors_ & 1) {
            d.quad_fold_en_i = 0;
            for (int k = 0; k < 3; ++k) setBits(d.quad_s_i, k * CW, CW, uint64_t(~s[k]));
            foldOk = tick() && foldOk;
            for (int k = 0; k < 3; ++k) setBits(d.quad_s_i, k * CW, CW, uint64_t(s[k]));
            d.quad_fold_en_i = 1;
        }
        d.quad_fold_first_i = 0;
        foldOk = eval() && foldOk;
        const int64_t fq = getSigned(d.quad_fold_q_o, 0, FW);
        int64_t fg[3];
        for (int k = 0; k < 3; ++k) fg[k] = getSigned(d.quad_fold_gradq_o, k * GW, GW);
        const bool foldMatch = fq == q && fg[0] == gq[0] && fg[1] == gq[1] && fg[2] == gq[2];
        t.check(assertOk && serialOk && foldOk && rq == q && rg[0] == gq[0] && rg[1] == gq[1] && rg[2] == gq[2] &&
                    serialMatch && foldMatch,
                [&] {
                    std::ostringstream os;
                    if (!assertOk || !serialOk || !foldOk) os << "  (an RTL assertion fired)\n";
                    os << "  s " << list(s, 3) << "\n  coef " << list(coef, 10) << "\n  golden q " << q << " gradq "
                       << list(gq, 3) << "\n  rtl    q " << rq << " gradq " << list(rg, 3) << "\n  serial q (live) "
                       << sq[0] << " gradq " << list(sg[0], 3) << "\n  serial q (held) " << sq[1] << " gradq "
                       << list(sg[1], 3) << "\n  folded q " << fq << " gradq " << list(fg, 3);
                    return os.str();
                });
        return q;
    }

    void term(Tally& t, int64_t n, const int64_t g[3], int64_t a, const int64_t gm[9]) {
        Vpst_arith_unit_top& d = *top_;
        setBits(d.term_n_i, 0, NW, uint64_t(n));
        for (int k = 0; k < 3; ++k) setBits(d.term_g_i, k * NGW, NGW, uint64_t(g[k]));
        setBits(d.term_a_i, 0, AW, uint64_t(a));
        for (int k = 0; k < 9; ++k) setBits(d.term_gm_i, k * GMW, GMW, uint64_t(gm[k]));
        const bool assertOk = eval();
        int64_t ft, gt[3];
        pst::octaveTermFx(P, n, g, a, gm, &ft, gt);
        const int64_t rf = getSigned(d.term_fterm_o, 0, FW);
        int64_t rg[3];
        for (int k = 0; k < 3; ++k) rg[k] = getSigned(d.term_gterm_o, k * GW, GW);
        t.check(assertOk && rf == ft && rg[0] == gt[0] && rg[1] == gt[1] && rg[2] == gt[2], [&] {
            std::ostringstream os;
            if (!assertOk) os << "  (an RTL assertion fired)\n";
            os << "  n " << n << " g " << list(g, 3) << " a " << a << "\n  gm " << list(gm, 9) << "\n  golden fterm "
               << ft << " gterm " << list(gt, 3) << "\n  rtl    fterm " << rf << " gterm " << list(rg, 3);
            return os.str();
        });
    }

    // Filter width: the profile's norm (fw_w_o) and all three (fw_w_norm_o).
    int64_t width(Tally& t, const int64_t grad[3], const int64_t j[6]) {  // returns golden W
        Vpst_arith_unit_top& d = *top_;
        for (int k = 0; k < 3; ++k) setBits(d.fw_grad_i, k * GW, GW, uint64_t(grad[k]));
        for (int k = 0; k < 6; ++k) setBits(d.fw_j_i, k * JW, JW, uint64_t(j[k]));
        const bool assertOk = eval();
        int64_t gold[4], rtl[4];
        gold[0] = pst::filterWidthFx(P, grad, j);
        rtl[0] = int64_t(getBits(d.fw_w_o, 0, WW));
        Profile pn = P;
        const pst::GradNorm norms[3] = {pst::GradNorm::Euclid, pst::GradNorm::MaxHalfMin, pst::GradNorm::L1};
        for (int n = 0; n < 3; ++n) {
            pn.filterNorm = norms[n];
            gold[1 + n] = pst::filterWidthFx(pn, grad, j);
            rtl[1 + n] = int64_t(getBits(d.fw_w_norm_o, n * WW, WW));
        }
        bool serialOk = runSerial(d.ser_step_i, d.ser_adv_i, widthSteps() - 1, false);
        const int64_t ser = int64_t(getBits(d.fw_ser_w_o, 0, WW));
        // The serial euclidean norm (squares and square root over cycles) against euclid's golden.
        serialOk = runSerial(d.ser_step_i, d.ser_adv_i, widthSteps(true) - 1, false) && serialOk;
        const int64_t serEuclid = int64_t(getBits(d.fw_ser_euclid_w_o, 0, WW));
        t.check(assertOk && serialOk && gold[0] == rtl[0] && gold[1] == rtl[1] && gold[2] == rtl[2] &&
                    gold[3] == rtl[3] && gold[0] == ser && gold[1] == serEuclid,
                [&] {
                    std::ostringstream os;
                    if (!assertOk || !serialOk) os << "  (an RTL assertion fired)\n";
                    os << "  grad " << list(grad, 3) << "\n  j " << list(j, 6)
                       << "\n  golden W (profile, euclid, mhm, l1) " << list(gold, 4)
                       << "\n  rtl    W (profile, euclid, mhm, l1) " << list(rtl, 4) << "\n  serial W (profile) " << ser << ", serial euclid W " << serEuclid;
                    return os.str();
                });
        return gold[0];
    }

    void isqrt(Tally& t, uint64_t x) {
        Vpst_arith_unit_top& d = *top_;
        setBits(d.sqrt_x_i, 0, SqW, x);
        const bool assertOk = eval();
        const uint64_t r = getBits(d.sqrt_y_o, 0, WW + 1);
        const uint64_t g = pst::isqrtFx(x);
        const unsigned __int128 rr = (unsigned __int128)r * r, r1 = (unsigned __int128)(r + 1) * (r + 1);
        t.check(assertOk && r == g && rr <= x && r1 > x, [&] {
            std::ostringstream os;
            if (!assertOk) os << "  (an RTL assertion fired)\n";
            os << "  x " << x << "  golden " << g << "  rtl " << r;
            return os.str();
        });
    }

    // pst_floor_sat config c (pst_arith_unit_top's fs_* table) on x against shiftSatSigned.
    struct FloorSatFormat {
        int inW, inFrac, outW, outFrac;
    };
    static constexpr FloorSatFormat kFloorSat[5] = {{40, 20, 16, 8}, {12, 4, 20, 10}, {20, 6, 10, 6},
                                                    {10, 2, 6, 6}, {60, 30, 48, 20}};
    void floorSat(Tally& t, int c, int64_t x) {
        Vpst_arith_unit_top& d = *top_;
        const FloorSatFormat& f = kFloorSat[c];
        setBits(d.fs_x_i, 64 * c, f.inW, uint64_t(x));
        const bool assertOk = eval();
        const int64_t r = getSigned(d.fs_y_o, 64 * c, f.outW);
        const int64_t g = pst::shiftSatSigned(x, f.inFrac - f.outFrac, f.outW);
        t.check(assertOk && r == g, [&] {
            std::ostringstream os;
            os << "  format " << c << " (" << f.inW << "." << f.inFrac << " -> " << f.outW << "." << f.outFrac
               << ")  x " << x << "  golden " << g << "  rtl " << r;
            return os.str();
        });
    }

    static std::unique_ptr<VerilatedContext> ctx_;
    static std::unique_ptr<Vpst_arith_unit_top> top_;
    int foldVectors_ = 0;   // quadric vectors so far (every other one gets a stalled edge)
};
std::unique_ptr<VerilatedContext> ArithUnit::ctx_;
std::unique_ptr<Vpst_arith_unit_top> ArithUnit::top_;

// Random vectors per test: 100,000 under ctest -L long, a tenth by default (unit_seed.h).
const int kRandom = pst::unit::randomCount(100000);

TEST_F(ArithUnit, Quadric) {
    ASSERT_LE(CW, 64);
    Rng rng(1);
    Tally special{"quadric special"}, boundary{"quadric saturation boundaries"}, random{"quadric random"};
    int64_t s[3], c[10];
    // Every input at its min or max, all 2^13 combinations; then zeros with one input extreme.
    for (int mask = 0; mask < (1 << 13); ++mask) {
        for (int k = 0; k < 3; ++k) s[k] = (mask >> k) & 1 ? fx::maxSigned(CW) : fx::minSigned(CW);
        for (int k = 0; k < 10; ++k) c[k] = (mask >> (3 + k)) & 1 ? fx::maxSigned(QW) : fx::minSigned(QW);
        quadric(special, s, c);
    }
    for (int i = 0; i < 13; ++i) {
        for (int64_t v : {int64_t(0), int64_t(1), int64_t(-1), fx::minSigned(i < 3 ? CW : QW),
                          fx::maxSigned(i < 3 ? CW : QW)}) {
            for (int k = 0; k < 3; ++k) s[k] = 0;
            for (int k = 0; k < 10; ++k) c[k] = 0;
            (i < 3 ? s[i] : c[i - 3]) = v;
            quadric(special, s, c);
            // ... and against a random background.
            for (int k = 0; k < 3; ++k) s[k] = rng.sval(CW);
            for (int k = 0; k < 10; ++k) c[k] = rng.sval(QW);
            (i < 3 ? s[i] : c[i - 3]) = v;
            quadric(special, s, c);
        }
    }

    // Saturation boundaries: floor(q to FFrac) = K exactly for K = FMax - 1 .. FMax + 1 and
    // FMin - 1 .. FMin + 1, with q = A s^2 + 2 s t (B = 1): A = floor(Y / s^2), t = floor(R / 2s),
    // so q lies within 2s below Y = K 2^QSh + 2^(QSh-1).
    const int qsh = P.quadric.fracBits + 2 * P.coord.fracBits - P.f.fracBits;
    const int gsh = P.quadric.fracBits + P.coord.fracBits - P.grad.fracBits;
    long hitsQ = 0, hitsG = 0;
    const int64_t fmax = fx::maxSigned(FW), fmin = fx::minSigned(FW);
    const int64_t gmax = fx::maxSigned(GW), gmin = fx::minSigned(GW);
    for (int i = 0; i < 600 && qsh >= 3; ++i) {
        const int64_t Ks[] = {fmax - 1, fmax, fmax + 1, fmin - 1, fmin, fmin + 1};
        const i128 K = Ks[i % 6];
        const i128 Y = K * (i128(1) << qsh) + (i128(1) << (qsh - 1));
        const int L = std::min(CW - 1, qsh - 2);
        const i128 s0 = i128((uint64_t(1) << (L - 1)) | rng.bits(L - 1));
        const i128 A = floorDiv(Y, s0 * s0), R = Y - A * s0 * s0, t0 = floorDiv(R, 2 * s0);
        if (!fits(A, QW) || !fits(t0, CW)) continue;
        for (int k = 0; k < 10; ++k) c[k] = 0;
        c[0] = int64_t(A);
        c[1] = 1;
        s[0] = int64_t(s0), s[1] = int64_t(t0), s[2] = 0;
        int64_t q, gq[3];
        pst::quadricFx(P, s, c, &q, gq);
        hitsQ += q == fx::satSigned(K, FW);
        quadric(boundary, s, c);
    }
    // grad q_r = floor(2 v_r to GradFrac) = K exactly: v_r = Q_rr s_r + 1 * s_c = V with
    // V = K 2^(GSh-1) + 2^(GSh-2), Q_rr = floor(V / s_r), s_c = the remainder.
    for (int i = 0; i < 600 && gsh >= 2; ++i) {
        const int64_t Ks[] = {gmax - 1, gmax, gmax + 1, gmin - 1, gmin, gmin + 1};
        const i128 K = Ks[i % 6];
        const int r = int(rng.range(0, 2)), cc = (r + 1) % 3;
        const int diag[3] = {0, 4, 7}, off[3] = {1, 5, 2};  // Q_rr and Q_r,(r+1)%3 of A..J
        const i128 V = K * (i128(1) << (gsh - 1)) + (i128(1) << (gsh - 2));
        const i128 sr = i128((uint64_t(1) << (CW - 3)) | rng.bits(CW - 3));
        const i128 Qrr = floorDiv(V, sr), rem = V - Qrr * sr;
        if (!fits(Qrr, QW)) continue;
        for (int k = 0; k < 10; ++k) c[k] = 0;
        c[diag[r]] = int64_t(Qrr);
        c[off[r]] = 1;
        for (int k = 0; k < 3; ++k) s[k] = 0;
        s[r] = int64_t(sr);
        s[cc] = int64_t(rem);
        int64_t q, gq[3];
        pst::quadricFx(P, s, c, &q, gq);
        hitsG += gq[r] == fx::satSigned(K, GW);
        quadric(boundary, s, c);
    }
    std::printf("arith_unit[%s]: quadric boundary hits: q %ld, grad q %ld\n", P.name.c_str(), hitsQ, hitsG);
    EXPECT_GT(hitsQ, 100);
    EXPECT_GT(hitsG, 100);

    long sat = 0;
    for (int i = 0; i < kRandom; ++i) {
        if (i % 2) {  // any magnitudes
            for (int k = 0; k < 3; ++k) s[k] = rng.sval(CW);
            for (int k = 0; k < 10; ++k) c[k] = rng.sval(QW);
        } else {  // magnitudes aimed at q around the F range: bits(c) + 2 bits(s) ~ QSh + FW
            const int tb = int(rng.range(std::max(0, qsh - 8), qsh + FW + 2));
            const int sb = int(rng.range(0, std::min(CW - 1, tb / 2)));
            for (int k = 0; k < 3; ++k) s[k] = rng.svalBits(CW, sb);
            for (int k = 0; k < 10; ++k) c[k] = rng.svalBits(QW, tb - 2 * sb);
        }
        const int64_t q = quadric(random, s, c);
        sat += q == fmax || q == fmin;
    }
    std::printf("arith_unit[%s]: quadric random: %ld of %d with q saturated\n", P.name.c_str(), sat, kRandom);
    EXPECT_EQ(special.mismatches + boundary.mismatches + random.mismatches, 0);
}

TEST_F(ArithUnit, OctaveTerm) {
    Rng rng(2);
    Tally special{"octave term special"}, boundary{"octave term saturation boundaries"},
        random{"octave term random"};
    int64_t n, g[3], a, gm[9];
    // Every input at its min or max: 2^14 combinations.
    for (int mask = 0; mask < (1 << 14); ++mask) {
        n = mask & 1 ? fx::maxSigned(NW) : fx::minSigned(NW);
        for (int k = 0; k < 3; ++k) g[k] = (mask >> (1 + k)) & 1 ? fx::maxSigned(NGW) : fx::minSigned(NGW);
        a = (mask >> 4) & 1 ? fx::maxSigned(AW) : fx::minSigned(AW);
        for (int k = 0; k < 9; ++k) gm[k] = (mask >> (5 + k)) & 1 ? fx::maxSigned(GMW) : fx::minSigned(GMW);
        term(special, n, g, a, gm);
    }
    // Zeros with one input at a special value, on a zero and on a random background.
    for (int i = 0; i < 14; ++i) {
        const int w = i == 0 ? NW : i < 4 ? NGW : i == 4 ? AW : GMW;
        for (int64_t v : {int64_t(0), int64_t(1), int64_t(-1), fx::minSigned(w), fx::maxSigned(w)}) {
            for (int bg = 0; bg < 2; ++bg) {
                n = bg ? rng.sval(NW) : 0;
                a = bg ? rng.sval(AW) : 0;
                for (int k = 0; k < 3; ++k) g[k] = bg ? rng.sval(NGW) : 0;
                for (int k = 0; k < 9; ++k) gm[k] = bg ? rng.sval(GMW) : 0;
                int64_t* slot = i == 0 ? &n : i < 4 ? &g[i - 1] : i == 4 ? &a : &gm[i - 5];
                *slot = v;
                term(special, n, g, a, gm);
            }
        }
    }
    // gterm_r = K exactly (where the Grad format can saturate): X = GM_r0 g0 + GM_r2 g0 +
    // GM_r1 g1 with g0 = max, GM_r0 = GM_r2 = floor(T / 2 g0), g1 in [2^(sh-3), 2^(sh-2)),
    // GM_r1 = floor(rem / g1): X lies within 2^(sh-2) below T = K 2^sh + 2^(sh-1).
    const int gsh = P.gradMatrix.fracBits + P.noiseOutFrac - P.grad.fracBits;
    const int64_t gmax = fx::maxSigned(GW), gmin = fx::minSigned(GW);
    long hits = 0, tried = 0;
    for (int i = 0; i < 600 && gsh >= 4; ++i) {
        const int64_t Ks[] = {gmax - 1, gmax, gmax + 1, gmin - 1, gmin, gmin + 1};
        const i128 K = Ks[i % 6];
        const int r = int(rng.range(0, 2));
        const i128 T = K * (i128(1) << gsh) + (i128(1) << (gsh - 1));
        const i128 g0 = fx::maxSigned(NGW), g1 = i128((uint64_t(1) << (gsh - 4)) | rng.bits(gsh - 4));
        const i128 m0 = floorDiv(T, 2 * g0), rem = T - 2 * m0 * g0, m1 = floorDiv(rem, g1);
        if (!fits(m0, GMW) || !fits(m1, GMW) || !fits(g1, NGW)) continue;  // out of reach
        ++tried;
        n = rng.sval(NW), a = rng.sval(AW);
        for (int k = 0; k < 9; ++k) gm[k] = rng.sval(GMW);
        gm[3 * r + 0] = int64_t(m0), gm[3 * r + 1] = int64_t(m1), gm[3 * r + 2] = int64_t(m0);
        g[0] = int64_t(g0), g[1] = int64_t(g1), g[2] = int64_t(g0);
        int64_t ft, gt[3];
        pst::octaveTermFx(P, n, g, a, gm, &ft, gt);
        hits += gt[r] == fx::satSigned(K, GW);
        term(boundary, n, g, a, gm);
    }
    // Whether the formats can saturate at all in this profile: |a n| <= 2^(AW+NW-2),
    // |GM . g| <= 3 2^(GMW+NGW-2).
    const int fsh = P.amplitude.fracBits + P.noiseOutFrac - P.f.fracBits;
    const bool fReach = fx::floorShift(i128(1) << (AW + NW - 2), fsh) > fx::maxSigned(FW);
    const bool gReach = fx::floorShift(3 * (i128(1) << (GMW + NGW - 2)), gsh) > fx::maxSigned(GW);
    std::printf("arith_unit[%s]: octave term: fterm saturation %s; gterm saturation %s, boundary hits "
                "%ld of %ld constructed\n",
                P.name.c_str(), fReach ? "reachable (format extremes cover it)" : "unreachable",
                gReach ? "reachable" : "unreachable", hits, tried);
    if (gReach) {
        EXPECT_GT(tried, 100);
    }
    EXPECT_EQ(hits, tried);

    for (int i = 0; i < kRandom; ++i) {
        n = rng.sval(NW), a = rng.sval(AW);
        for (int k = 0; k < 3; ++k) g[k] = rng.sval(NGW);
        for (int k = 0; k < 9; ++k) gm[k] = rng.sval(GMW);
        term(random, n, g, a, gm);
    }
    EXPECT_EQ(special.mismatches + boundary.mismatches + random.mismatches, 0);
}

TEST_F(ArithUnit, FilterWidth) {
    Rng rng(3);
    Tally special{"filter width special"}, boundary{"filter width W boundaries"}, random{"filter width random"};
    int64_t gr[3], j[6];
    // Every input at min, 0 or max: 3^9 combinations.
    int pow3 = 1;
    for (int k = 0; k < 9; ++k) pow3 *= 3;
    for (int m = 0; m < pow3; ++m) {
        int x = m;
        for (int k = 0; k < 9; ++k, x /= 3) {
            const int w = k < 3 ? GW : JW;
            const int64_t v = x % 3 == 0 ? fx::minSigned(w) : x % 3 == 1 ? 0 : fx::maxSigned(w);
            (k < 3 ? gr[k] : j[k - 3]) = v;
        }
        width(special, gr, j);
    }
    // Exact Wx, Wy: grad = (G0, G1, G2), dsdx = (j0, 1, 0), dsdy = (j3, 0, 1):
    // gx = G0 j0 + G1, gy = G0 j3 + G2, with G1, G2 remainders: gx = Kx 2^Sh + (random low bits).
    const int sh = P.grad.fracBits + P.jacobian.fracBits - P.log2Clut - P.widthFrac;
    const int64_t wmax = fx::maxUnsigned(WW);
    long built = 0;
    auto exact = [&](int64_t kx, int64_t ky) {
        if (sh < 1) return;
        const i128 g0 = i128((uint64_t(1) << (GW - 3)) | rng.bits(GW - 3));
        const i128 tx = i128(kx) * (i128(1) << sh) + i128(rng.bits(sh));
        const i128 ty = i128(ky) * (i128(1) << sh) + i128(rng.bits(sh));
        const i128 j0 = floorDiv(tx, g0), j3 = floorDiv(ty, g0);
        if (!fits(j0, JW) || !fits(j3, JW)) return;
        gr[0] = int64_t(g0), gr[1] = int64_t(tx - j0 * g0), gr[2] = int64_t(ty - j3 * g0);
        j[0] = int64_t(j0), j[1] = 1, j[2] = 0, j[3] = int64_t(j3), j[4] = 0, j[5] = 1;
        ++built;
        width(boundary, gr, j);
    };
    auto sgn = [&](int64_t v) { return (rng.g() & 1) ? -v : v; };
    for (int i = 0; i < 400; ++i) {
        // One axis at and around WMax, and far beyond.
        for (int64_t k : {wmax - 1, wmax, wmax + 1, wmax + 2, 2 * wmax, int64_t(0), int64_t(1)}) {
            exact(sgn(k), 0);
            exact(0, sgn(k));
        }
        // L1 = WMax - 1 .. WMax + 1.
        const int64_t a = rng.range(0, wmax);
        for (int d = -1; d <= 1; ++d) exact(sgn(a), sgn(wmax + d - a));
        // max + floor(min / 2) = WMax, WMax + 1.
        const int64_t mn = rng.range(0, wmax / 2);
        for (int d = 0; d <= 1; ++d) exact(sgn(wmax + d - mn / 2), sgn(mn));
        // Euclid: around the circle of radius WMax + 1, and Pythagorean triples (exact roots).
        const int64_t kx = rng.range(0, wmax);
        const int64_t ky = int64_t(pst::isqrtFx((unsigned __int128)(wmax + 1) * (wmax + 1) -
                                                (unsigned __int128)kx * kx));
        for (int d = -1; d <= 1; ++d) exact(sgn(kx), sgn(ky + d));
        const int64_t t = rng.range(0, wmax / 4);
        exact(sgn(3 * t), sgn(4 * t));
        exact(sgn(5 * t / 2), sgn(12 * t / 5));
    }
    std::printf("arith_unit[%s]: filter width: %ld constructed exact (Wx, Wy) vectors\n", P.name.c_str(), built);
    EXPECT_GT(built, 1000);

    long sat = 0, zero = 0;
    for (int i = 0; i < kRandom; ++i) {
        if (i % 2) {  // any magnitudes
            for (int k = 0; k < 3; ++k) gr[k] = rng.sval(GW);
            for (int k = 0; k < 6; ++k) j[k] = rng.sval(JW);
        } else {  // magnitudes aimed at W in range: bits(grad) + bits(j) ~ Sh + WW
            const int tb = int(rng.range(std::max(0, sh - 4), sh + WW + 2));
            const int gb = int(rng.range(std::max(0, tb - (JW - 1)), std::min(GW - 1, tb)));
            for (int k = 0; k < 3; ++k) gr[k] = rng.svalBits(GW, gb);
            for (int k = 0; k < 6; ++k) j[k] = rng.svalBits(JW, tb - gb);
        }
        const int64_t w = width(random, gr, j);
        sat += w == wmax;
        zero += w == 0;
    }
    std::printf("arith_unit[%s]: filter width random: %ld of %d with W = WMax, %ld with W = 0\n",
                P.name.c_str(), sat, kRandom, zero);
    EXPECT_EQ(special.mismatches + boundary.mismatches + random.mismatches, 0);
}

TEST_F(ArithUnit, Isqrt) {
    ASSERT_LE(SqW, 64);
    Rng rng(4);
    Tally special{"isqrt special"}, random{"isqrt random"};
    const uint64_t xmax = SqW >= 64 ? ~uint64_t(0) : (uint64_t(1) << SqW) - 1;
    const uint64_t rmax = pst::isqrtFx(xmax);
    for (uint64_t x = 0; x < 4096; ++x) isqrt(special, x);
    for (uint64_t x : {xmax, xmax - 1, rmax * rmax, rmax * rmax - 1, rmax * rmax + 1}) isqrt(special, x);
    // Perfect squares and their neighbours, roots log-uniform up to the largest.
    for (int i = 0; i < 5000; ++i) {
        const uint64_t k = std::min<uint64_t>(rng.uval(WW + 1), rmax);
        const uint64_t k2 = k * k;
        isqrt(special, k2);
        if (k2 > 0) isqrt(special, k2 - 1);
        if (k2 < xmax) isqrt(special, k2 + 1);
    }
    for (int i = 0; i < kRandom; ++i) isqrt(random, rng.uval(SqW));
    EXPECT_EQ(special.mismatches + random.mismatches, 0);
}

// The serial units take the step counts the golden model (and docs/HARDWARE.md) give.
TEST_F(ArithUnit, SerialStepCounts) {
    EXPECT_EQ(quadricSteps(), pst::quadricSerialSteps(P));
    EXPECT_EQ(widthSteps(), pst::filterWidthSerialSteps(P));  // the profile's norm
    EXPECT_LE(quadricSteps() - 1, pst::contract::kStepMax);
    EXPECT_LE(widthSteps(true) - 1, pst::contract::kStepMax);
}

TEST_F(ArithUnit, FloorSat) {
    Rng rng(5);
    Tally special{"floor_sat special"}, random{"floor_sat random"};
    for (int c = 0; c < 5; ++c) {
        const FloorSatFormat& f = kFloorSat[c];
        const int sh = f.inFrac - f.outFrac;
        const int64_t lo = fx::minSigned(f.inW), hi = fx::maxSigned(f.inW);
        // The input extremes and the values around each saturation threshold (where the
        // shifted value leaves the output range), clipped to the input range.
        std::vector<int64_t> xs = {lo, hi, 0, -1, 1, lo + 1, hi - 1};
        for (const i128 edge : {i128(fx::maxSigned(f.outW)) + 1, i128(fx::minSigned(f.outW))}) {
            const i128 x0 = sh >= 0 ? edge * (i128(1) << sh) : floorDiv(edge, i128(1) << -sh);
            for (int dx = -2; dx <= 2; ++dx)
                if (x0 + dx >= lo && x0 + dx <= hi) xs.push_back(int64_t(x0 + dx));
        }
        for (int64_t x : xs) floorSat(special, c, x);
        for (int i = 0; i < kRandom / 10; ++i) floorSat(random, c, rng.sval(f.inW));
    }
    EXPECT_EQ(special.mismatches + random.mismatches, 0);
}

}  // namespace
