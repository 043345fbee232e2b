// The golden model of pst_top: the same register map, the same units and the same rounding
// as the RTL (docs/HARDWARE.md), bit for bit. It can return every unit's intermediate values
// for one fragment, and it can perturb one unit on purpose (to show that the scoreboard
// catches and names it).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "contract.h"
#include "profile.h"

namespace pst {

class ClutFilterFx;

// One fragment as the hardware sees it: fixed-point s (Coord format) and J (Jacobian format).
struct FragmentFx {
    uint32_t tag = 0;
    int64_t s[3] = {0, 0, 0};
    int64_t j[6] = {0, 0, 0, 0, 0, 0};  // ds/dx, dt/dx, dr/dx, ds/dy, dt/dy, dr/dy
};

// The units of the pipeline (docs/HARDWARE.md "Units"), in data-flow order (the scoreboard names
// the first that differs).
enum class Unit { Transform, Noise, Quadric, Accumulate, FilterWidth, ClutFilter, Count };
const char* toString(Unit u);

struct UnitTrace {
    static constexpr int kMaxOctaves = contract::kOctavesMax;
    int octaves = 0;                        // active octaves
    int lat[kMaxOctaves][3] = {};           // unit 1: lattice index (after + LatticeOffset, mod 2^LatticeBits)
    int64_t frac[kMaxOctaves][3] = {};      // unit 1: lattice fraction
    int64_t n[kMaxOctaves] = {};            // unit 2: noise value
    int64_t g[kMaxOctaves][3] = {};         // unit 2: noise gradient
    int64_t q = 0, gradq[3] = {};           // unit 3
    int64_t lgx = 0, lgy = 0;               // unit 4, bandlimited octaves: lg |dsdx|, lg |dsdy| (fadeLgFx)
    int64_t alpha[kMaxOctaves] = {};        // unit 4: the octave's fade (2^FadeFrac = whole)
    int64_t fterm[kMaxOctaves] = {};        // unit 4 terms (faded)
    int64_t gterm[kMaxOctaves][3] = {};
    int64_t f = 0, grad[3] = {};            // unit 4 result
    int64_t w = 0;                          // unit 5: W = w N in entries
    uint32_t rgba = 0;                      // unit 6: packed RGBA, R at bit 0

    std::string describe(const Profile& p) const;  // one line per unit, raw and as numbers
};

// The output of the pipeline for one fragment (what the RTL's output port carries).
struct PixelFx {
    uint32_t tag = 0;
    uint32_t rgba = 0;
    int64_t f = 0;
    int64_t grad[3] = {0, 0, 0};
    int64_t w = 0;
};

class GoldenPipeline {
public:
    explicit GoldenPipeline(const Profile& profile);
    ~GoldenPipeline();
    GoldenPipeline(const GoldenPipeline&);
    GoldenPipeline& operator=(const GoldenPipeline&);

    const Profile& profile() const { return profile_; }
    // A register write (docs/HARDWARE.md register map), as on pst_top's register port.
    void write(uint16_t addr, uint32_t data);
    // The whole pipeline for one fragment.
    PixelFx eval(const FragmentFx& frag, UnitTrace* trace = nullptr) const;

    // Adds one LSB to the named unit's result (Unit::Count = no fault): for scoreboard tests.
    void injectFault(Unit s) { fault_ = s; }

private:
    Profile profile_;
    Unit fault_ = Unit::Count;
    uint32_t ctrl_ = 0;
    int active_ = 0;
    int64_t quad_[contract::kRegQuadricCount] = {};
    int64_t worley_[contract::kRegWorleyCount] = {};  // the worley unit's C_k
    struct Octave {
        int64_t m[contract::kRegOctaveMCount] = {}, o[contract::kRegOctaveOCount] = {}, a = 0,
                gm[contract::kRegOctaveGmCount] = {}, lgm = 0, fm = 0;
    };
    int64_t fade_[contract::kFadeEntries] = {};  // the fade table (filter.bandlimit profiles)
    int64_t wcap_ = -1;  // the filter-width cap (filter.width_cap profiles; -1: reset, all ones)
    std::vector<Octave> oct_;
    std::unique_ptr<ClutFilterFx> clut_;
};

// Pixel equality on every output field.
bool operator==(const PixelFx& a, const PixelFx& b);

}  // namespace pst
