// Colour-table filter, bit for bit with rtl/colour/pst_clut_filter.sv (conventions in the header and
// in the module header), and the driver's table builder.
#include "clut_filter_fx.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "contract.h"
#include "fixed.h"

namespace pst {
namespace {

using fx::i128;

uint64_t mask(int bits) { return bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1; }

uint32_t channel(uint32_t rgba, int c, int cb) { return (rgba >> (c * cb)) & uint32_t(mask(cb)); }

void checkProfile(const Profile& p) {
    auto fail = [&](const std::string& why) {
        throw std::invalid_argument("colour-table filter, profile '" + p.name + "': " + why);
    };
    if (p.log2Clut < 1 || p.log2Clut > 11) fail("log2_clut must be 1..11 (register map ranges)");
    if (p.colourBits < 1 || p.colourBits > 8) fail("colour_bits must be 1..8 (RGBA in one 32-bit word)");
    if (p.filterRecipFrac < 1 || p.filterRecipFrac > 40) fail("recip_frac must be 1..40");
    if (p.widthFrac < 0 || p.log2Clut - 1 + p.widthFrac < 1) fail("width_frac too small (blend weight needs >= 1 bit)");
    if (p.f.intBits < 1 || p.f.fracBits < 0 || p.f.width() > 62) fail("f format must be 1..62 bits");
}

}  // namespace

const char* toString(ClutCase c) {
    switch (c) {
        case ClutCase::Point: return "point";
        case ClutCase::MipLevel: return "mip";
        case ClutCase::SatMean: return "sat mean (mod, W >= N)";
        case ClutCase::SatEntry: return "sat single entry";
        case ClutCase::SatInside: return "sat inside";
        case ClutCase::SatWrap: return "sat wrap (mod)";
        case ClutCase::SatBelow: return "sat past bottom (clamp)";
        case ClutCase::SatAbove: return "sat past top (clamp)";
        case ClutCase::SatBoth: return "sat past both ends (clamp)";
    }
    return "?";
}

// ---- driver side ---------------------------------------------------------------------------

uint32_t quantizeColour(const Profile& p, const glm::dvec4& c) {
    const double maxC = double(mask(p.colourBits));
    uint32_t rgba = 0;
    for (int k = 0; k < 4; ++k) {
        double v = c[k];
        if (std::isnan(v)) v = 0.0;
        v = std::clamp(v, 0.0, 1.0);
        const uint32_t q = uint32_t(std::llround(v * maxC));  // round half away from zero
        rgba |= q << (k * p.colourBits);
    }
    return rgba;
}

ClutTables buildClutTables(const Profile& p, const std::vector<glm::dvec4>& colours) {
    checkProfile(p);
    const int N = p.clutSize(), cb = p.colourBits;
    if (int(colours.size()) != N)
        throw std::invalid_argument("buildClutTables: " + std::to_string(colours.size()) + " colours, profile '" +
                                    p.name + "' needs " + std::to_string(N));
    ClutTables t;
    t.clut.resize(N);
    for (int e = 0; e < N; ++e) t.clut[e] = quantizeColour(p, colours[e]);

    // Summed-area table, eq. 13, exact in ColourBits + Log2Clut bits.
    t.sat.resize(N);
    std::array<uint32_t, 4> acc{0, 0, 0, 0};
    for (int e = 0; e < N; ++e) {
        for (int c = 0; c < 4; ++c) acc[c] += channel(t.clut[e], c, cb);
        t.sat[e] = acc;
    }

    // MIP levels 1..Log2Clut: entry j of level k = round half up of the mean of level-0
    // entries j 2^k .. (j+1) 2^k - 1 = (csat[(j+1)2^k - 1] - csat[j 2^k - 1] + 2^(k-1)) >> k.
    t.mip.assign(N - 1, 0);
    for (int k = 1; k <= p.log2Clut; ++k) {
        const int base = N - (N >> (k - 1)), size = N >> k;
        for (int j = 0; j < size; ++j) {
            uint32_t rgba = 0;
            for (int c = 0; c < 4; ++c) {
                const int last = ((j + 1) << k) - 1, first = j << k;
                const uint64_t s = uint64_t(t.sat[last][c]) - (first > 0 ? t.sat[first - 1][c] : 0u);
                const uint64_t m = (s + (uint64_t(1) << (k - 1))) >> k;
                rgba |= uint32_t(m) << (c * cb);
            }
            t.mip[base + j] = rgba;
        }
    }
    return t;
}

std::vector<std::pair<uint16_t, uint32_t>> clutRegisterWrites(const Profile& p, const ClutTables& t) {
    const int N = p.clutSize();
    if (int(t.clut.size()) != N || int(t.sat.size()) != N || int(t.mip.size()) != N - 1)
        throw std::invalid_argument("clutRegisterWrites: table sizes do not match profile '" + p.name + "'");
    std::vector<std::pair<uint16_t, uint32_t>> w;
    w.reserve(size_t(6 * N));
    for (int e = 0; e < N; ++e) w.push_back({uint16_t(contract::kRegClut + e), t.clut[e]});
    for (int e = 0; e < N; ++e)
        for (int c = 0; c < 4; ++c)
            w.push_back({uint16_t(contract::kRegSat + contract::kRegSatStride * e + c), t.sat[e][c]});
    for (int e = 0; e < N - 1; ++e) w.push_back({uint16_t(contract::kRegMip + e), t.mip[e]});
    return w;
}

bool isClutTableAddress(const Profile& p, uint16_t addr) {
    using namespace contract;
    const int N = p.clutSize(), a = addr;
    return (a >= kRegClut && a < kRegClut + N) || (a >= kRegSat && a < kRegSat + kRegSatStride * N) ||
           (a >= kRegMip && a < kRegMip + N);
}

// ---- the filter ----------------------------------------------------------------------------

ClutFilterFx::ClutFilterFx(const Profile& p) {
    checkProfile(p);
    log2N_ = p.log2Clut;
    n_ = 1 << log2N_;
    cb_ = p.colourBits;
    wf_ = p.widthFrac;
    rf_ = p.filterRecipFrac;
    fw_ = p.f.width();
    ww_ = p.widthBits();
    p_ = std::max(wf_ + 1, p.f.fracBits - log2N_);  // u and W/2 both exact at P fraction bits
    uShift_ = log2N_ - p.f.fracBits + p_;            // f -> u at P: f 2^(Log2Clut - FFrac + P)
    hShift_ = p_ - wf_ - 1;                           // W -> W/2 at P
    countBits_ = log2N_ + 3;                          // count <= ceil(W) <= 4N
    satBits_ = cb_ + log2N_;                          // csat[N-1] <= N (2^CB - 1)
    tFrac_ = log2N_ - 1 + wf_;                        // W / 2^L - 1 exact for L <= Log2Clut - 1
    t_.clut.assign(n_, 0);
    t_.sat.assign(n_, {0, 0, 0, 0});
    t_.mip.assign(n_, 0);  // entry N-1 is writable but never read
    recip_.assign(size_t(4 * n_ + 1), 0);
    for (uint64_t c = 1; c <= uint64_t(4 * n_); ++c) recip_[c] = uint32_t(((uint64_t(1) << (rf_ + 1)) + c) / (2 * c));
}

void ClutFilterFx::write(uint16_t addr, uint32_t data) {
    const uint32_t a = addr;
    const uint32_t rgbaMask = uint32_t(mask(4 * cb_)), satMask = uint32_t(mask(satBits_));
    const uint32_t satSpan = uint32_t(contract::kRegSatStride * n_);  // a power of two
    if ((a >> log2N_) == (uint32_t(contract::kRegClut) >> log2N_)) {
        t_.clut[a & uint32_t(n_ - 1)] = data & rgbaMask;
    } else if (a / satSpan == contract::kRegSat / satSpan) {
        const uint32_t i = a % satSpan;
        t_.sat[i / contract::kRegSatStride][i % contract::kRegSatStride] = data & satMask;
    } else if ((a >> log2N_) == (uint32_t(contract::kRegMip) >> log2N_)) {
        t_.mip[a & uint32_t(n_ - 1)] = data & rgbaMask;
    }
}

void ClutFilterFx::load(const ClutTables& t) {
    if (int(t.clut.size()) != n_ || int(t.sat.size()) != n_ || int(t.mip.size()) != n_ - 1)
        throw std::invalid_argument("ClutFilterFx::load: table sizes do not match the profile");
    for (int e = 0; e < n_; ++e) write(uint16_t(contract::kRegClut + e), t.clut[e]);
    for (int e = 0; e < n_; ++e)
        for (int c = 0; c < 4; ++c) write(uint16_t(contract::kRegSat + contract::kRegSatStride * e + c), t.sat[e][c]);
    for (int e = 0; e < n_ - 1; ++e) write(uint16_t(contract::kRegMip + e), t.mip[e]);
}

uint32_t ClutFilterFx::level(int k, uint32_t j) const {
    if (k == 0) return t_.clut[j];
    return t_.mip[uint32_t(n_ - (n_ >> (k - 1))) + j];
}

uint32_t ClutFilterFx::filter(int64_t fIn, int64_t wIn, bool clamp, int kind, ClutTrace* trace) const {
    ClutTrace tr;
    const int N = n_, L = log2N_;
    const uint32_t Nm = uint32_t(N - 1);
    const uint32_t maxC = uint32_t(mask(cb_));
    const int64_t f = fx::wrapSigned(fIn, fw_);
    const uint64_t W = fx::wrapUnsigned(wIn, ww_);

    // u = f N at P fraction bits; iu = floor(u); point index by mod or clamp.
    const i128 uP = i128(f) * (i128(1) << uShift_);
    const int64_t iu = int64_t(uP >> p_);
    const uint32_t pidx = clamp ? (iu < 0 ? 0u : iu > int64_t(Nm) ? Nm : uint32_t(iu)) : uint32_t(uint64_t(iu) & Nm);
    tr.iu = iu;
    tr.pidx = pidx;

    uint32_t out = 0;
    const int k = kind & 3;
    const uint64_t wInt = W >> wf_;
    if (k == 0 || ((k == 1 || k == 2) && wInt == 0)) {
        tr.kase = ClutCase::Point;
        out = t_.clut[pidx];
    } else if (k == 1 || k == 2) {
        // MIP: level Lc = min(floor(lg W), Log2Clut), blended to the next with linear t.
        int lw = 0;
        while ((wInt >> (lw + 1)) != 0) ++lw;
        const int lc = std::min(lw, L), lb = std::min(lc + 1, L);
        const uint32_t a = level(lc, pidx >> lc), b = level(lb, pidx >> lb);
        const uint64_t t = (k == 2 && lw < L) ? ((W << (L - 1 - lw)) & mask(tFrac_)) : 0;
        for (int c = 0; c < 4; ++c) {
            const int64_t ca = channel(a, c, cb_), cbv = channel(b, c, cb_);
            const int64_t acc = (ca << tFrac_) + (cbv - ca) * int64_t(t) + (int64_t(1) << (tFrac_ - 1));
            out |= uint32_t(acc >> tFrac_) << (c * cb_);
        }
        tr.kase = ClutCase::MipLevel;
        tr.level = lc;
        tr.t = t;
    } else {
        // SAT: window entries lo+1..hi.
        const i128 hwP = i128(W) << hShift_;
        const int64_t lo = int64_t((uP - hwP) >> p_), hi = int64_t((uP + hwP) >> p_);
        const uint32_t count = uint32_t(uint64_t(hi - lo) & mask(countBits_));
        tr.lo = lo;
        tr.hi = hi;
        tr.count = count;
        const auto& csat = t_.sat;
        uint64_t sum[4] = {0, 0, 0, 0};
        bool divide = true;
        if (!clamp) {
            const uint32_t hm = uint32_t(uint64_t(hi) & Nm), lm = uint32_t(uint64_t(lo) & Nm);
            if ((W >> (wf_ + L)) != 0) {  // W >= N: the whole table's mean
                tr.kase = ClutCase::SatMean;
                divide = false;
                for (int c = 0; c < 4; ++c)  // at CB bits (a mean of CB-bit entries fits)
                    out |= uint32_t(((uint64_t(csat[Nm][c]) + uint64_t(N / 2)) >> L) & maxC) << (c * cb_);
            } else if (count == 0) {
                tr.kase = ClutCase::SatEntry;
                divide = false;
                out = t_.clut[hm];
            } else {
                const bool wrap = hm <= lm;
                tr.kase = wrap ? ClutCase::SatWrap : ClutCase::SatInside;
                for (int c = 0; c < 4; ++c)
                    sum[c] = uint64_t(csat[hm][c]) + (wrap ? uint64_t(csat[Nm][c]) : 0) - uint64_t(csat[lm][c]);
            }
        } else {
            const uint32_t hidx = hi < 0 ? 0u : hi > int64_t(Nm) ? Nm : uint32_t(hi);
            if (count == 0 || lo >= int64_t(Nm) || hi < 0) {
                tr.kase = ClutCase::SatEntry;
                divide = false;
                out = t_.clut[hidx];
            } else {
                const bool below = lo < -1, above = hi >= int64_t(N);
                const uint64_t nb = below ? uint64_t(-(lo + 1)) & mask(countBits_) : 0;
                const uint64_t na = above ? uint64_t(hi - int64_t(Nm)) & mask(countBits_) : 0;
                tr.kase = below && above ? ClutCase::SatBoth
                          : below        ? ClutCase::SatBelow
                          : above        ? ClutCase::SatAbove
                                         : ClutCase::SatInside;
                for (int c = 0; c < 4; ++c) {
                    const uint64_t lsat = lo < 0 ? 0 : csat[uint32_t(lo)][c];
                    sum[c] = nb * channel(t_.clut[0], c, cb_) + csat[hidx][c] - lsat +
                             na * channel(t_.clut[Nm], c, cb_);
                }
            }
        }
        if (divide) {
            // The sums are held at SumBits = ColourBits + Log2Clut + 2 bits (they fit for tables
            // built by buildClutTables; arbitrary RAM contents wrap as in the RTL).
            const uint64_t r = recip(count);
            tr.recip = uint32_t(r);
            for (int c = 0; c < 4; ++c) {
                sum[c] &= mask(cb_ + log2N_ + 2);
                tr.sum[c] = sum[c];
                const uint64_t q = uint64_t((i128(sum[c]) * r + (i128(1) << (rf_ - 1))) >> rf_);
                out |= uint32_t(std::min<uint64_t>(q, maxC)) << (c * cb_);
            }
        }
    }
    if (trace) *trace = tr;
    return out;
}

}  // namespace pst
