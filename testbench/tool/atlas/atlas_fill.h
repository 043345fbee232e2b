// Filling an atlas through the texture pipeline: each texel is a fragment (its s and its
// Jacobian ds/du, ds/dv per texel, so the filter width antialiases the atlas itself), shaded by
// the double reference and, for a hardware profile, by the golden model and the verilated RTL
// with every pixel scoreboarded bit for bit (input gaps and output stalls as SimOptions says).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "atlas.h"
#include "render.h"
#include "rtl_model.h"
#include "scene.h"

namespace pst {

struct AtlasFill {
    Image reference;            // size x size RGBA, double model; background texels (0, 0, 0, 0)
    Image hardware;             // the RTL's (or the golden model's without RTL); empty without a profile
    long long texels = 0;
    double referenceSeconds = 0, goldenSeconds = 0, rtlSeconds = 0;
    bool passed = true;         // scoreboard: 0 mismatches, nothing lost or out of order
    size_t mismatches = 0;
    std::string scoreboard;
    uint64_t cycles = 0;        // RTL cycles streaming the texels (fill and drain included)
    std::vector<std::string> notes;
};

// Reference only.
AtlasFill fillAtlasReference(const Scene& scene, const Atlas& atlas, int threads = 0);
// Reference, golden model, and the RTL when rtl != nullptr.
AtlasFill fillAtlas(const Scene& scene, const Atlas& atlas, const Profile& profile, RtlModel* rtl,
                    size_t maxReports = 8);

}  // namespace pst
