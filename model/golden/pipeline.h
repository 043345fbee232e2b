// The golden model of pst_top: the same register map, the same stages and the same rounding
// as the RTL (docs/HARDWARE.md), bit for bit. It can return every stage's intermediate values
// for one fragment, and it can perturb one stage on purpose (to show that the scoreboard
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

// The stages of the pipeline, in data-flow order (the scoreboard names the first that differs).
enum class Stage { Transform, Noise, Quadric, Accumulate, FilterWidth, ClutFilter, Count };
const char* toString(Stage s);

struct StageTrace {
    static constexpr int kMaxOctaves = contract::kOctavesMax;
    int octaves = 0;                        // active octaves
    int lat[kMaxOctaves][3] = {};           // stage 1: lattice index (after + LatticeOffset, mod 2^LatticeBits)
    int64_t frac[kMaxOctaves][3] = {};      // stage 1: lattice fraction
    int64_t n[kMaxOctaves] = {};            // stage 2: noise value
    int64_t g[kMaxOctaves][3] = {};         // stage 2: noise gradient
    int64_t q = 0, gradq[3] = {};           // stage 3
    int64_t lgx = 0, lgy = 0;               // stage 4, bandlimited octaves: lg |dsdx|, lg |dsdy| (fadeLgFx)
    int64_t alpha[kMaxOctaves] = {};        // stage 4: the octave's fade (2^FadeFrac = whole)
    int64_t fterm[kMaxOctaves] = {};        // stage 4 terms (faded)
    int64_t gterm[kMaxOctaves][3] = {};
    int64_t f = 0, grad[3] = {};            // stage 4 result
    int64_t w = 0;                          // stage 5: W = w N in entries
    uint32_t rgba = 0;                      // stage 6: packed RGBA, R at bit 0

    std::string describe(const Profile& p) const;  // one line per stage, raw and as numbers
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
    PixelFx eval(const FragmentFx& frag, StageTrace* trace = nullptr) const;

    // Adds one LSB to the named stage's result (Stage::Count = no fault): for scoreboard tests.
    void injectFault(Stage s) { fault_ = s; }

private:
    Profile profile_;
    Stage fault_ = Stage::Count;
    uint32_t ctrl_ = 0;
    int active_ = 0;
    int64_t quad_[contract::kRegQuadricCount] = {};
    int64_t worley_[contract::kRegWorleyCount] = {};  // the worley unit's C_k
    struct Octave {
        int64_t m[contract::kRegOctaveMCount] = {}, o[contract::kRegOctaveOCount] = {}, a = 0,
                gm[contract::kRegOctaveGmCount] = {}, lgm = 0;
    };
    int64_t fade_[contract::kFadeEntries] = {};  // the fade table (filter.bandlimit profiles)
    std::vector<Octave> oct_;
    std::unique_ptr<ClutFilterFx> clut_;
};

// Pixel equality on every output field.
bool operator==(const PixelFx& a, const PixelFx& b);

}  // namespace pst
