// Rendering a scene through the hardware models: the driver programs each object's texture,
// the fragments of each layer stream through the RTL (and the golden model), the scoreboard
// checks every pixel bit for bit, and the image is compared with the double reference.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "render.h"
#include "rtl_model.h"
#include "scene.h"

namespace pst {

struct HwRenderOptions {
    size_t maxReports = 8;      // first mismatches kept with their unit traces
    bool probes = true;         // sample the octave-stage probes (names early units)
    Unit fault = Unit::Count;  // perturb a golden unit on purpose (scoreboard self-test)
    int truthSamples = 0;       // n > 0: also compare with the n x n supersampled ground truth
    std::function<void(const std::string&, double)> progress;
};

// Hardware image against the reference, over RGB.
struct ErrorStats {
    double maxLsb = 0;        // largest |hardware - reference| in colour LSBs
    double rms = 0;           // in [0, 1] units
    double psnr = 0;          // dB
    double within1Lsb = 0;    // % of pixels with every RGB channel within 1 LSB
};

struct HwRenderResult {
    Image hardware;           // RTL output (or the golden model's without RTL), RGBA in [0, 1]
    Image reference;          // reference model, filtered
    Image difference;         // |hardware - reference| x 8, RGB
    bool passed = true;       // zero mismatches, nothing lost or out of order
    size_t pixels = 0, mismatches = 0;
    std::string scoreboard;   // the scoreboard's summary
    std::map<Unit, size_t> byUnit;    // mismatches by first differing unit
    uint64_t cycles = 0;      // RTL cycles spent streaming (fill and drain included)
    long long fragments = 0;
    double cyclesPerPixel = 0;
    double rtlSeconds = 0, goldenSeconds = 0, referenceSeconds = 0;
    ErrorStats vsReference;
    ErrorStats vsTruth;       // only with truthSamples > 0
    ErrorStats referenceVsTruth;  // the double reference's own error against the ground truth
    std::vector<std::string> notes;   // what the driver had to change (octaves dropped, ...)
    uint64_t firstMismatchCycle = UINT64_MAX;  // RTL cycle at which the first mismatching pixel came
                                               // out (for a lost pixel: the end of its batch)
};

// `rtl` may be null: golden model only (no scoreboard, no cycles).
HwRenderResult renderHardware(const Scene& scene, const Profile& profile, RtlModel* rtl,
                              const HwRenderOptions& options = {});

class Scoreboard;

// One batch of fragments through the golden model (its pixels; with an RTL model also the
// scoreboard's expectations and unit traces) and through the RTL model (each pixel observed by
// the scoreboard, with the octave-stage probes when `probes`). Adds each model's time to
// goldenSeconds and rtlSeconds. Returns the pixels to show: the RTL's when it ran, else the
// golden model's. Used by the scene render and the atlas fill.
std::vector<PixelFx> runBatch(GoldenPipeline& golden, RtlModel* rtl, Scoreboard& board,
                              const std::vector<FragmentFx>& in, int activeOctaves, bool probes,
                              double& goldenSeconds, double& rtlSeconds,
                              uint64_t* firstMismatchCycle = nullptr);

ErrorStats compareToReference(const Image& hardware, const Image& reference, int colourBits);

}  // namespace pst
