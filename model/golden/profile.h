// A hardware profile (rtl/configs/NAME.toml): the widths and choices of one build of the
// pipeline. The RTL gets the same numbers as -G parameters through scripts/profile.py; the
// schema (keys, ranges, enums, cross-constraints) is rtl/contract.toml's, through contract.h.
#pragma once

#include <array>
#include <string>

#include "contract.h"
#include "noise.h"
#include "texture.h"

namespace pst {

// A signed two's-complement format: `intBits` integer bits including the sign, `fracBits`
// fraction bits; value = integer / 2^fracBits.
struct FixedFormat {
    int intBits = 0;
    int fracBits = 0;
    int width() const { return intBits + fracBits; }
};

// How the quadric, filter-width and colour-table units are built: every product every cycle
// (parallel), or one row / one channel per cycle (serial: fewer multipliers; the octave
// transform and term rows take 3 + 3 more cycles per pixel, see rtl/pst_octave_stage.sv; needs
// noise_steps >= 4). The arithmetic is the same bit for bit.
// The order is rtl/contract.toml's (pipeline.datapath), checked by profile_test.
enum class Datapath { Parallel, Serial };

struct Profile {
    std::string name;
    std::string path;

    // [pipeline]
    int octaves = 8;        // K noise terms held
    int noiseUnits = 8;     // noise units in parallel
    int noiseSteps = 1;     // cycles per noise evaluation (1, 2, 4, 8)
    int log2Clut = 8;       // N = 2^log2Clut colour-table entries
    int colourBits = 8;     // bits per RGBA channel
    Datapath datapath = Datapath::Parallel;
    int noiseRegs = 0;      // pipeline registers in each noise unit (0..6)
    int octaveRegs = 0;     // pipeline registers around it: 1 after the term, 2 also after the transform
    int widthRegs = 0;      // pipeline registers in the parallel filter width
    int colourRegs = 0;     // pipeline registers in the colour-table filter
    // [noise] (noise.basis: hardwareBasis of interp / corner / hash)
    NoiseOptions noise;
    int noiseValueFrac = 15;    // R table fraction bits
    int noiseLatticeFrac = 16;  // fraction bits of T_i s into the noise unit
    int noiseOutFrac = 16;      // noise value and gradient fraction bits
    int noiseGuardBits = 4;     // fraction bits of the noise unit's nodes below noiseOutFrac
    int noiseGradFrac = 20;     // fraction bits kept on the derivative lanes (noise_fx.h noiseGradFloor)
    // noise.worley_search != none: the noise unit is a worley unit (noise.basis Worley;
    // noise.search, noise.maxPoints, noise.cubes = Rom256 say which variant), F1..F_worleyOrder.
    int worleyOrder = 2;
    // [filter]
    GradNorm filterNorm = GradNorm::Euclid;
    int filterRecipFrac = 18;
    bool bandlimit = false;     // filter.bandlimit = "isotropic": the fade unit (pst_octave_fade) is built
    // [formats]
    FixedFormat coord, jacobian, matrix, offset, amplitude, gradMatrix, quadric, f, grad;
    int widthFrac = 8;

    int clutSize() const { return 1 << log2Clut; }
    int octavePasses() const { return (octaves + noiseUnits - 1) / noiseUnits; }
    // The octave stage's nominal cycles per fragment (rtl/pst_octave_stage.sv Cycles): the
    // pipeline's rate as long as the other serial units are shorter (docs/HARDWARE.md lists
    // every stage's cycles; a profile whose serial quadric, quadricSerialSteps, takes longer
    // runs at the quadric's rate). Used for simulation timeouts; `pst regress` reports the
    // measured rate.
    // The pipeline registers add latency only, except on the serial datapath, where the
    // fragment waits in the octave stage for its last pass's noise and term registers.
    int cyclesPerPixel() const {
        return octavePasses() * noiseSteps +
               (datapath == Datapath::Serial
                    ? contract::kSerialOctaveExtraCycles + noiseRegs + (octaveRegs >= 1 ? 1 : 0)
                    : 0);
    }

    // W = w N in entries: unsigned, log2Clut + 2 integer bits, widthFrac fraction bits.
    int widthIntBits() const { return log2Clut + 2; }

    // Every key's value indexed by RTL parameter (contract::Param): what a verilated model
    // was built from, compared by sameHardware().
    std::array<int, contract::kNumParams> params{};
};

// "" when a and b describe the same hardware (every key equal), else the first key that
// differs ("formats.coord").
std::string profileDifference(const Profile& a, const Profile& b);

// Reads and checks a profile; throws InputError naming file, line and field.
Profile loadProfile(const std::string& path);
// The noise basis a hardware noise variant computes: Perlin2002 for Perlin's 2002 triple
// (quintic, grad12, perlin256; the contract allows it only whole), Rayshade otherwise.
NoiseBasis hardwareBasis(const NoiseOptions& n);
Profile parseProfile(const std::string& text, const std::string& path);
// "full" -> <source>/rtl/configs/full.toml; a path is used as it is.
std::string profilePath(const std::string& nameOrPath, const std::string& sourceDir);

}  // namespace pst
