// Constrained-random regression: random textures and random fragment streams through the
// verilated pipeline of one profile, every pixel checked against the golden model bit for bit.
//
// The stream is cut into segments; each segment gets a fresh RTL model (its own random input
// gaps and output stalls) and a fresh golden model, and is a few batches long. Each batch
// programs a texture through the driver (testbench/verify/driver: programTexture, or only the
// control register, as a driver does for the unfiltered image) and streams K fragments. Every
// draw comes from the run's seed and the segment's index, so any fragment can be replayed by
// starting at its segment (RandomRegressOptions::from) and sees the same inputs, gaps and
// stalls as in the full run.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pipeline.h"
#include "profile.h"
#include "texture.h"

namespace pst {

// A small deterministic generator (splitmix64): the same stream on every platform and
// standard library, so a seed replays anywhere.
class RandomStream {
public:
    explicit RandomStream(uint64_t seed) : s_(seed) {}
    uint64_t next();
    double uniform();                                  // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    int64_t range(int64_t lo, int64_t hi);             // [lo, hi] inclusive
    bool chance(double p) { return uniform() < p; }

private:
    uint64_t s_;
};

// A value of a fixed-point format, as a double: zero, the extremes, a log-uniform magnitude
// up to 2^maxExp, any integer of the format, or beyond the format (the driver saturates).
double randomFormatValue(RandomStream& r, const FixedFormat& f, int maxExp);

// A random texture for profile p: quadric, 0..octaves+1 octaves (M, o, a), a random colour
// table of the profile's size (random, ramps, constant, stripes), wrap and filter kind.
Texture randomTexture(RandomStream& r, const Profile& p);
// A random fragment stream in the hardware's input formats: s over the whole Coord range or
// small, on lattice planes (integer components), J zero, small, or at the format's extremes.
std::vector<FragmentFx> randomFragments(RandomStream& r, const Profile& p, uint32_t firstTag, size_t n);

struct RandomRegressOptions {
    uint64_t seed = 1;
    uint64_t fragments = 100000;   // fragments to check (counted from `from`)
    uint64_t from = 0;             // replay: start at the segment holding this fragment index
    int maxBatch = 2048;           // fragments per texture: uniform in [1, maxBatch]
    int batchesPerSegment = 8;     // textures per RTL model instance
    double maxGapRate = 0.5;       // each segment draws its gap and stall rates in [0, max]
    double maxStallRate = 0.5;
    bool probes = false;           // sample the octave-stage probes (names the first bad unit)
    Unit fault = Unit::Count;      // self-test: perturb this golden unit ...
    uint64_t faultFrom = 0;        // ... from this fragment index on
    uint64_t injectAssert = UINT64_MAX;  // self-test: once this fragment is in the RTL, the driver
                                   // writes a register while the pipeline is busy (an assertion fires)
    size_t maxReports = 4;
    std::function<void(uint64_t done, uint64_t total)> progress;
};

struct RandomRegressResult {
    bool passed = true;
    uint64_t fragments = 0;        // fragments checked
    uint64_t firstFragment = 0;    // index of the first one (the segment start of `from`)
    uint64_t textures = 0;         // texture programs (full or control only)
    uint64_t segments = 0;
    uint64_t mismatches = 0;       // includes lost and out-of-order pixels
    uint64_t firstBad = UINT64_MAX;  // global index of the first mismatching fragment (for an
                                   // assertion: the oldest fragment in the pipeline when it fired)
    uint64_t replayFragments = 1;  // fragments from firstBad a replay runs (`--random N --from
                                   // firstBad`): 1 for a mismatch; for an assertion to the end of
                                   // its segment, as a younger fragment in flight may have caused it
    bool assertion = false;        // an RTL assertion fired (the simulator printed which)
    uint64_t assertionCycle = 0;   // the segment model's cycle at which it fired
    uint64_t cycles = 0;           // RTL cycles streaming
    double seconds = 0;            // wall clock of the whole run
    double rtlSeconds = 0;         // of which in the verilated model (register writes and streaming)
    double goldenSeconds = 0;      // of which in the golden model (evaluating the same fragments)
    std::string report;            // the scoreboard's first failures
};

// The global index of the first fragment of the segment that holds fragment `index`.
uint64_t segmentStart(const RandomRegressOptions& o, uint64_t index, uint64_t* segment = nullptr);
// The first fragment of every segment a run of `o` simulates (from segmentStart(o.from) up to
// o.from + o.fragments): where a run can be split with no fragment simulated twice.
std::vector<uint64_t> segmentStarts(const RandomRegressOptions& o);

// Runs the regression on the verilated model `rtlName` (one of rtlProfiles()).
RandomRegressResult runRandomRegress(const Profile& p, const std::string& rtlName,
                                     const RandomRegressOptions& o);

}  // namespace pst
