// Unit test of rtl/colour/pst_clut_filter.sv against the golden model (model/golden/clut_filter_fx.cpp),
// one verilated top per profile: every output bit must match.
//
// Per table: random colours (noise, harsh 0/1, ramps) built by the driver's buildClutTables and
// written through the write port, interleaved with writes to addresses outside the table
// ranges (both sides must ignore them); then special vectors (W = 0, just below 1, 1, N +- 1
// LSB, max; f = min/max of its format, 0, +-1 LSB, u on entry boundaries and half-way, near
// both ends), then random vectors from a printed seed (PST_SEED replays a run). Each (f, W) is
// evaluated for all 8 (clamp, kind) combinations. The first mismatches are printed with their
// inputs and the golden model's trace.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <verilated.h>

#include "Vpst_clut_filter.h"
#include "clut_filter_fx.h"
#include "contract.h"
#include "fixed.h"
#include "profile.h"
#include "unit/unit_seed.h"

namespace {

using pst::ClutFilterFx;
using pst::ClutTrace;
using pst::Profile;
using pst::fx::i128;
namespace fx = pst::fx;
using pst::contract::kRegClut;
using pst::contract::kRegMip;
using pst::contract::kRegSat;
using pst::contract::kRegSatStride;

// --- Port access: any verilated port type (CData..QData or VlWide<N>), fields <= 64 bits ---
template <typename T>
void setPort(T& p, int width, uint64_t v) {
    p = T(v & (width >= 64 ? ~uint64_t(0) : (uint64_t(1) << width) - 1));
}
template <std::size_t N>
void setPort(VlWide<N>& p, int width, uint64_t v) {
    for (int i = 0; i < int(N); ++i) p[i] = 0;
    for (int b = 0; b < width && b < 64; ++b)
        if ((v >> b) & 1) p[b / 32] |= 1u << (b % 32);
}
template <typename T>
uint64_t getPort(const T& p) {
    return uint64_t(p);
}
template <std::size_t N>
uint64_t getPort(const VlWide<N>& p) {
    return uint64_t(p[0]) | (N > 1 ? uint64_t(p[1]) << 32 : 0);
}

using pst::unit::prof;
uint64_t seed() { return pst::unit::seed("clut_unit"); }

int vectorsPerTable() {
    const char* e = std::getenv("PST_CLUT_VECTORS");
    return e ? std::atoi(e) : pst::unit::randomCount(40000);   // 40,000 under ctest -L long
}

// The DUT and the golden model side by side, fed the same writes.
class Bench {
public:
    Bench() : ctx_(std::make_unique<VerilatedContext>()), top_(std::make_unique<Vpst_clut_filter>(ctx_.get())), gold_(prof()) {
        const Profile& p = prof();
        fw_ = p.f.width();
        ww_ = p.widthBits();
        top_->clk_i = 0;
        top_->we_i = 0;
        top_->rst_ni = 1;
        top_->step_i = 0;
        top_->adv_i = 0;
        top_->eval();
    }
    ~Bench() { top_->final(); }

    void write(uint16_t addr, uint32_t data, bool we = true) {
        top_->we_i = we;
        setPort(top_->addr_i, 16, addr);
        setPort(top_->wdata_i, 32, data);
        tick();
        top_->we_i = 0;
        if (we) gold_.write(addr, data);
    }

    // One (f, W, clamp, kind): returns true on a match; prints the first mismatches.
    bool check(int64_t f, int64_t W, bool clamp, int kind) {
        setPort(top_->f_i, fw_, uint64_t(f));
        setPort(top_->w_i, ww_, uint64_t(W));
        top_->clamp_i = clamp;
        top_->kind_i = kind;
        top_->rst_ni = 1;
        top_->eval();  // settle the inputs before any clock edge
        // Serial datapath: channels 0..2 one per cycle (stored), channel 3 live at step 3.
        if (prof().datapath == pst::Datapath::Serial) {
            for (int step = 0; step < 3; ++step) {
                top_->step_i = step;
                top_->adv_i = 1;
                tick();
            }
            top_->adv_i = 0;
            top_->step_i = 3;
        }
        top_->eval();
        const uint64_t rtl = getPort(top_->rgba_o);
        ClutTrace tr;
        const uint32_t gold = gold_.filter(f, W, clamp, kind, &tr);
        tick();  // clocks the assertions (we_i is low)
        ++checked_;
        if (rtl == gold) return true;
        if (++mismatches_ <= 10) {
            std::printf("MISMATCH f=%lld (%.9g) W=%lld (%.6g entries) %s kind %d: rtl %08llx golden %08x "
                        "[%s: iu %lld pidx %u lo %lld hi %lld count %u recip %u level %d t %llu]\n",
                        (long long)f, fx::toDouble(f, prof().f.fracBits), (long long)W,
                        fx::toDouble(W, prof().widthFrac), clamp ? "clamp" : "mod", kind, (unsigned long long)rtl, gold,
                        pst::toString(tr.kase), (long long)tr.iu, tr.pidx, (long long)tr.lo, (long long)tr.hi,
                        tr.count, tr.recip, tr.level, (unsigned long long)tr.t);
        }
        return false;
    }
    // All 8 (clamp, kind) combinations.
    void checkAll(int64_t f, int64_t W) {
        for (int clamp = 0; clamp < 2; ++clamp)
            for (int kind = 0; kind < 4; ++kind) check(f, W, clamp != 0, kind);
    }

    long checked() const { return checked_; }
    long mismatches() const { return mismatches_; }
    const ClutFilterFx& golden() const { return gold_; }

private:
    void tick() {
        top_->clk_i = 1;
        top_->eval();
        top_->clk_i = 0;
        top_->eval();
    }
    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<Vpst_clut_filter> top_;
    ClutFilterFx gold_;
    int fw_ = 0, ww_ = 0;
    long checked_ = 0, mismatches_ = 0;
};

std::vector<glm::dvec4> randomColours(int n, std::mt19937_64& rng, int style) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::vector<glm::dvec4> c(n);
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 4; ++k) {
            switch (style % 3) {
                case 0: c[i][k] = U(rng); break;
                case 1: c[i][k] = U(rng) < 0.5 ? 0.0 : 1.0; break;
                default: c[i][k] = double((i * (k + 1)) % n) / double(n) + 0.01 * U(rng); break;
            }
        }
    return c;
}

// Loads a table through the write port, with writes to unmapped addresses in between.
void loadTables(Bench& b, std::mt19937_64& rng, int style) {
    const Profile& p = prof();
    const int N = p.clutSize();
    const auto writes = pst::clutRegisterWrites(p, pst::buildClutTables(p, randomColours(N, rng, style)));
    auto unmapped = [&]() -> uint16_t {
        for (;;) {
            const uint16_t a = uint16_t(rng());
            if (!pst::isClutTableAddress(p, a)) return a;
        }
    };
    for (const auto& w : writes) {
        b.write(w.first, w.second);
        if (rng() % 8 == 0) b.write(unmapped(), uint32_t(rng()));
        if (rng() % 16 == 0) b.write(uint16_t(kRegClut + rng() % N), uint32_t(rng()), /*we=*/false);  // not written
    }
    // The last MIP address (entry N-1) is writable and never read: write junk there too.
    b.write(uint16_t(kRegMip + N - 1), uint32_t(rng()));
}

void specialVectors(Bench& b) {
    const Profile& p = prof();
    const int N = p.clutSize(), fw = p.f.width(), ww = p.widthBits(), wf = p.widthFrac;
    const int64_t fMin = fx::minSigned(fw), fMax = fx::maxSigned(fw), wMax = fx::maxUnsigned(ww);
    auto fOfU = [&](double u) { return fx::satSigned(i128(std::llround(std::ldexp(u / N, p.f.fracBits))), fw); };
    const int64_t one = int64_t(1) << wf, n = int64_t(N) << wf;
    std::vector<int64_t> ws = {0, 1, one - 1, one, one + 1, 2 * one, 3 * one, n / 2, n - 1, n, n + 1,
                               2 * n, 3 * n, wMax - 1, wMax};
    for (int k = 1; k < p.widthIntBits(); ++k) {  // every MIP level boundary (W < 2^widthIntBits)
        ws.push_back((int64_t(1) << k << wf) - 1);
        ws.push_back(int64_t(1) << k << wf);
        ws.push_back((int64_t(3) << k << wf) / 2);
    }
    std::vector<int64_t> fs = {fMin, fMin + 1, fMax, fMax - 1, 0, 1, -1};
    for (double u : {-1.0, -0.5, 0.5, 1.0, double(N) / 2, double(N) - 1, double(N) - 0.5, double(N), double(N) + 0.5,
                     -double(N), 2.0 * N, 3.0 * N, -3.0 * N}) {
        fs.push_back(fOfU(u));
        fs.push_back(fOfU(u) + 1);
        fs.push_back(fOfU(u) - 1);
    }
    for (int64_t f : fs)
        for (int64_t W : ws) b.checkAll(f, std::clamp<int64_t>(W, 0, wMax));
}

void randomVectors(Bench& b, std::mt19937_64& rng, int count) {
    const Profile& p = prof();
    const int N = p.clutSize(), fw = p.f.width(), ww = p.widthBits();
    const int64_t fMin = fx::minSigned(fw), fMax = fx::maxSigned(fw), wMax = fx::maxUnsigned(ww);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto pick = [&](int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(rng); };
    auto fOfU = [&](double u) { return fx::satSigned(i128(std::llround(std::ldexp(u / N, p.f.fracBits))), fw); };
    auto wOf = [&](double W) { return fx::satUnsigned(i128(std::llround(std::ldexp(W, p.widthFrac))), ww); };
    for (int i = 0; i < count; ++i) {
        int64_t f, W;
        switch (pick(0, 5)) {
            case 0: f = pick(fMin, fMax); break;                        // anywhere (mostly far outside)
            case 1: f = fOfU(-N + 3.0 * N * U(rng)); break;             // [-N, 2N)
            case 2: f = fOfU(N * U(rng)); break;                        // inside
            case 3: f = fOfU(double(pick(-3, N + 3))); break;           // entry boundary
            case 4: f = fOfU((U(rng) < 0.5 ? 0.0 : double(N)) + 16.0 * (U(rng) - 0.5)); break;  // near the ends
            default: f = fOfU(double(pick(-3, N + 3)) + 0.5); break;    // half-way
        }
        switch (pick(0, 5)) {
            case 0: W = pick(0, (int64_t(1) << p.widthFrac) - 1); break;      // W < 1
            case 1: W = wOf(std::exp2(std::log2(4.0 * N) * U(rng))); break;    // log-uniform [1, 4N)
            case 2: W = (int64_t(N) << p.widthFrac) + pick(-2, 2); break;      // ~N
            case 3: W = wMax - pick(0, 16); break;                             // ~4N
            case 4: W = pick(0, 4 * N - 1) << p.widthFrac; break;              // integer
            default: W = pick(0, wMax); break;
        }
        b.checkAll(f, std::clamp<int64_t>(W, 0, wMax));
    }
}

TEST(ClutUnit, RandomTablesSpecialAndRandomVectors) {
    std::mt19937_64 rng(seed());
    Bench b;
    long specials = 0;
    for (int table = 0; table < 3; ++table) {  // noise, harsh 0/1, ramps
        loadTables(b, rng, table);
        const long before = b.checked();
        specialVectors(b);
        specials += b.checked() - before;
        randomVectors(b, rng, vectorsPerTable());
        ASSERT_EQ(b.mismatches(), 0) << "table " << table;
    }
    std::printf("clut_unit[%s]: %ld vectors ((f, W) x 8 clamp/kind; %ld special), %ld mismatches\n",
                prof().name.c_str(), b.checked(), specials, b.mismatches());
}

// Writes with we_i low do nothing; a rewrite of one entry changes exactly what it should.
TEST(ClutUnit, WriteEnableAndRewrite) {
    std::mt19937_64 rng(seed() ^ 0x5a5a5a5a);
    Bench b;
    loadTables(b, rng, 0);
    const int N = prof().clutSize();
    for (int k = 0; k < 64; ++k) {
        const uint16_t a = uint16_t(rng() % 3 == 0 ? kRegClut + rng() % N : rng() % 3 == 1 ? kRegSat + rng() % (kRegSatStride * N)
                                                                                         : kRegMip + rng() % (N - 1));
        b.write(a, uint32_t(rng()), /*we=*/false);
        b.write(uint16_t(a ^ 1), uint32_t(rng()));
        randomVectors(b, rng, 50);
    }
    EXPECT_EQ(b.mismatches(), 0);
}

}  // namespace
