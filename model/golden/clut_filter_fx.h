// Unit 6 of docs/HARDWARE.md, bit for bit: the colour-table filter (paper section 3.3) as
// rtl/colour/pst_clut_filter.sv computes it, plus the driver-side table builder.
//
// Tables (the hardware RAM contents, written through the register port):
//   clut[e]        e < N: RGBA packed, ColourBits each, R at bit 0                (reg clut + e)
//   csat[e][c]     e < N, c < 4: sum of the quantized entries 0..e of channel c,
//                  ColourBits + Log2Clut bits, exact (eq. 13)                     (reg sat + 4e + c)
//   mip[base(k)+j] MIP level k = 1..Log2Clut, entry j < N >> k, base(k) = N - (N >> (k-1))
//                  (level 1 at 0, level 2 at N/2, ..., level Log2Clut at N-2)     (reg mip + e)
// The driver quantizes each colour channel to round(c (2^ColourBits - 1)) (ties away from
// zero) after clamping c to [0, 1] (NaN -> 0). MIP entry j of level k is the mean of the
// 2^k quantized level-0 entries j 2^k .. (j+1) 2^k - 1, ROUNDED HALF UP ONCE:
// (S + 2^(k-1)) >> k with S their exact integer sum. That is the mean of 2 entries of the
// exact previous level (paper: "neighbouring colors are averaged"), rounded once, so every
// level is within 0.5 LSB of the reference's exact level (rounding level by level would drift
// by up to k/2 LSB).
//
// Filter arithmetic (identical to rtl/colour/pst_clut_filter.sv, which documents it in its header):
// f is QFInt.FFrac (wrapped to its width), W unsigned with Log2Clut+2 integer and WidthFrac
// fraction bits (wrapped to its width); u = f N.
//   P = max(WidthFrac + 1, FFrac - Log2Clut) fraction bits hold u and W/2 exactly;
//   iu = floor(u); point index pidx = clamp ? clamp(iu, 0, N-1) : iu mod N.
//   kind 0 (none): clut[pidx].
//   kind 1/2 (MIP): W < 1 -> clut[pidx]. Else Lw = leading-one position of floor(W),
//     Lc = min(Lw, Log2Clut); a = level Lc entry pidx >> Lc (level 0 = clut), b = level
//     min(Lc+1, Log2Clut) entry pidx >> (Lc+1); t = 0 for kind 1 or Lw >= Log2Clut, else
//     t = W / 2^Lw - 1 at TFrac = Log2Clut - 1 + WidthFrac bits (exact; the LINEAR
//     approximation of lg W - Lw); channel = (a 2^TFrac + (b - a) t + 2^(TFrac-1)) >> TFrac.
//   kind 3 (SAT): lo = floor(u - W/2), hi = floor(u + W/2), count = hi - lo (< 4N+1).
//     mod:   W >= N -> mean (csat[N-1] + N/2) >> Log2Clut (the paper's "w >= N" rule);
//            count 0 -> clut[hi mod N];
//            else sum = csat[hi mod N] - csat[lo mod N] + (hi mod N <= lo mod N ? csat[N-1] : 0)
//            (inside, or the paper's two wrap cases, which are the same formula in modular
//            indices; lo mod N = N-1 stands for csat[-1] = 0).
//     clamp: count 0, lo >= N-1 or hi < 0 -> clut[clamp(hi, 0, N-1)] (the window sees one
//            entry only); else sum = nb clut[0] + csat[min(hi, N-1)] - (lo < 0 ? 0 : csat[lo])
//            + na clut[N-1] with nb = lo < -1 ? -(lo+1) : 0 (past the bottom) and
//            na = hi >= N ? hi - (N-1) : 0 (past the top); both may be non-zero (past both).
//     (no W < 1 special case, as in ColorMap::filterSat: W = 0 is count 0 = clut[floor(u)]);
//     sums are held at ColourBits + Log2Clut + 2 bits (wrapping, as the RTL, if the RAMs hold
//     something else than a driver-built table);
//     channel = min(2^ColourBits - 1, (sum recip[count] + 2^(RF-1)) >> RF),
//            recip[c] = round(2^RF / c) = (2^(RF+1) + c) / (2c), RF = FilterRecipFrac.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "profile.h"

namespace pst {

// The colour-table RAM contents (see the header comment for the layout).
struct ClutTables {
    std::vector<uint32_t> clut;                // N entries, packed RGBA, R at bit 0
    std::vector<std::array<uint32_t, 4>> sat;  // N entries x RGBA running sums
    std::vector<uint32_t> mip;                 // N - 1 entries: levels 1..Log2Clut, packed RGBA
};

// Driver side: quantize `colours` (exactly N = 2^log2Clut of them, else std::invalid_argument)
// and build the summed-area table and the MIP levels in integer arithmetic.
ClutTables buildClutTables(const Profile& p, const std::vector<glm::dvec4>& colours);
// One colour to packed RGBA (round to nearest, clamp to [0, 1], NaN -> 0).
uint32_t quantizeColour(const Profile& p, const glm::dvec4& c);
// The register writes that load `t` (docs/HARDWARE.md map): clut, then SAT, then MIP.
std::vector<std::pair<uint16_t, uint32_t>> clutRegisterWrites(const Profile& p, const ClutTables& t);

// Which branch of the filter produced a result (for traces and tests).
enum class ClutCase {
    Point,       // kind 0, or MIP with W < 1
    MipLevel,    // MIP nearest / blended (Lc, t in the trace)
    SatMean,     // mod, W >= N: whole-table mean
    SatEntry,    // SAT window sees one entry (count 0; clamp: window entirely past one end)
    SatInside,   // window inside [0, N) (mod: no wrap)
    SatWrap,     // mod: window wraps past either end
    SatBelow,    // clamp: past the bottom only
    SatAbove,    // clamp: past the top only
    SatBoth,     // clamp: past both ends
};
const char* toString(ClutCase c);

struct ClutTrace {
    ClutCase kase = ClutCase::Point;
    int64_t iu = 0;          // floor(u)
    uint32_t pidx = 0;       // point index (mod / clamp)
    int64_t lo = 0, hi = 0;  // SAT window ends (entries lo+1..hi)
    uint32_t count = 0;      // SAT hi - lo
    uint64_t sum[4] = {};    // SAT sums per channel
    uint32_t recip = 0;      // recip[count]
    int level = 0;           // MIP level Lc
    uint64_t t = 0;          // MIP blend weight at tFrac bits
};

// Whether `addr` is in one of the table ranges (clut, sat, mip of contract.h) for this profile's
// N, written as ranges (the module and ClutFilterFx::write decode them by shifts).
bool isClutTableAddress(const Profile& p, uint16_t addr);

class ClutFilterFx {
public:
    explicit ClutFilterFx(const Profile& p);  // std::invalid_argument if the widths are unsupported

    // A register write (the module decodes the clut, sat and mip ranges of contract.h and
    // ignores other addresses).
    void write(uint16_t addr, uint32_t data);
    // Writes every table entry (same as the writes of clutRegisterWrites).
    void load(const ClutTables& t);

    // f: QFInt.FFrac; W: unsigned, Log2Clut+2 integer, WidthFrac fraction bits (both wrapped
    // to their port widths); kind 0 none, 1 MIP nearest, 2 MIP blended, 3 SAT (low 2 bits).
    // Returns packed RGBA, R at bit 0.
    uint32_t filter(int64_t f, int64_t W, bool clamp, int kind, ClutTrace* trace = nullptr) const;

    // The RAM contents as written (mip holds N entries here: entry N-1 is writable, never read).
    const ClutTables& tables() const { return t_; }
    uint32_t recip(uint32_t count) const { return count < recip_.size() ? recip_[count] : 0; }

    // Derived widths (the RTL's localparams of the same names).
    int n() const { return n_; }
    int fracP() const { return p_; }       // P: common fraction bits of u and W/2
    int countBits() const { return countBits_; }
    int satBits() const { return satBits_; }
    int tFrac() const { return tFrac_; }

private:
    uint32_t level(int k, uint32_t j) const;  // MIP level k (0 = clut) entry j

    int log2N_, n_, cb_, wf_, rf_, fw_, ww_, p_, uShift_, hShift_, countBits_, satBits_, tFrac_;
    ClutTables t_;
    std::vector<uint32_t> recip_;  // recip[c], c = 0..4N (recip[0] = 0, unused)
};

}  // namespace pst
