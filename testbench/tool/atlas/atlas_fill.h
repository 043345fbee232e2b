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

// The multipass GPU filler (Hart 2001, docs/MULTIPASS.md; atlas_fill_gpu.cpp): every octave's
// noise n_i(T_i s) of every texel by the multipass program on OpenGL ES 3 (one draw per pass;
// testbench/gpu), the rest on the host: f = q(s) + sum_i a_i (n_i - 1/2), the colour map's point
// sample at f (the paper's PixelMap). The same inputs through the bit-accurate CPU model
// (model/multipass/cpu_model.h), compared value for value.
struct GpuFillOptions {
    std::string variant = "sgi";  // sgi | rc | xor (multipass::Variant)
    int bf = 4;                   // fraction bits b_f of the 8-bit coordinates
    uint32_t seed = 1;            // the random tables' seed
};
struct GpuFill {
    Image image;                  // size x size RGBA; background texels (0, 0, 0, 0)
    long long texels = 0;
    std::string variant, interp, renderer, glVersion, eglPlatform;
    int b = 8, bf = 4, octaves = 0;  // octaves: noise runs (sum over the atlas's textures)
    int drawsPerOctave = 0, draws = 0;  // the program's draws (passes); draws = all runs'
    double seconds = 0;           // the GPU fill, wall clock: context, uploads, passes, readbacks, host sum
    double passSeconds = 0;       // the passes alone (glFinish to glFinish), all runs
    double cpuModelSeconds = 0;
    long long noiseValues = 0;    // texels x octaves compared with the CPU model
    long long cpuModelMismatches = 0;
    std::vector<std::string> notes;
};
// Whether this build has the GPU filler (EGL and GLESv2 found at configure time).
bool gpuFillerBuilt();
// Throws InputError ("EGL: ...") when no EGL device can be opened or the build has no EGL, and
// for a texture the multipass noise cannot stand for (a basis other than rayshade).
GpuFill fillAtlasGpu(const Scene& scene, const Atlas& atlas, const GpuFillOptions& options);

}  // namespace pst
