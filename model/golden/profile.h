// A hardware profile (rtl/configs/NAME.toml): the widths and choices of one build of the
// pipeline. The RTL gets the same numbers as -G parameters through scripts/profile.py; the
// schema (keys, ranges, enums, cross-constraints) is rtl/contract.toml's, through contract.h.
#pragma once

#include <string>

#include "contract.h"
#include "noise.h"
#include "texture.h"

namespace pst {

// How the quadric, filter-width and colour-table units are built (Datapath, generated from
// rtl/contract.toml pipeline.datapath into contract.h): every product every cycle (Parallel),
// or one row / one channel per cycle (Serial: fewer multipliers; the octave transform and term
// rows take 3 + 3 more cycles per pixel, see rtl/octave/pst_octave_stage.sv; needs noise_steps >= 4).
// The arithmetic is the same bit for bit.
//
// A profile: its keys (ProfileParams, generated from rtl/contract.toml into contract.h: one
// typed member per key, octaves .. widthFrac), its name and file, and the noise options the
// golden model's noise unit computes with (hardwareNoise of the noise keys).
struct Profile : ProfileParams {
    std::string name;
    std::string path;
    // The hardware's noise variant in the reference model's terms (basis: hardwareBasis of
    // interp / corner / hash; noise.worley_search != none: basis Worley, its search,
    // maxPoints = noiseWorleyPoints, cubes Rom256). Set by parseProfile from the keys; after
    // changing a noise key, set it again: p.noise = hardwareNoise(p).
    NoiseOptions noise;

    int clutSize() const { return 1 << log2Clut; }
    // The pipeline's clocks per pixel (contract::clocks_per_pixel: its slowest stage, the
    // docs/HARDWARE.md cycle table). Used for simulation timeouts; `pst regress` reports the
    // measured rate.
    int cyclesPerPixel() const {
        return contract::clocks_per_pixel(octaves, noiseUnits, noiseSteps, int(datapath), noiseRegs, octaveRegs,
                                          quadric.width(), coord.width(), int(filterNorm), log2Clut, widthFrac,
                                          colourRegs);
    }
    // W = w N in entries: unsigned, widthIntBits() integer bits, widthFrac fraction bits.
    int widthIntBits() const { return contract::w_int_bits(log2Clut); }
    int widthBits() const { return contract::w_width(log2Clut, widthFrac); }
    // filter.bandlimit = "isotropic": the fade unit (pst_octave_fade) is built.
    bool bandlimit() const { return filterBandlimit == FilterBandlimit::Isotropic; }
    // filter.width_cap = "on": the width cap (register wcap, the minimum in pst_width_stage) is built.
    bool widthCap() const { return filterWidthCap == FilterWidthCap::On; }
};

// "" when a and b describe the same hardware (every key equal), else the first key that
// differs ("formats.coord").
std::string profileDifference(const Profile& a, const Profile& b);

// Reads and checks a profile; throws InputError naming file, line and field.
Profile loadProfile(const std::string& path);
// The noise basis a hardware noise variant computes: Perlin2002 for Perlin's 2002 triple
// (quintic, grad12, perlin256; the contract allows it only whole), Rayshade otherwise.
NoiseBasis hardwareBasis(const NoiseOptions& n);
// The noise options of a profile's noise keys (Profile::noise).
NoiseOptions hardwareNoise(const ProfileParams& p);
Profile parseProfile(const std::string& text, const std::string& path);
// A profile argument ("full", "rtl/configs/full.toml", "mine.toml") is a file when it has a
// '/' in it or ends in ".toml", else the name of a profile in <source>/rtl/configs: the one
// rule every command line and test uses (scripts/pstlib/paths.py profile_path in Python).
bool isProfileFile(const std::string& nameOrPath);
// "full" -> <sourceDir>/rtl/configs/full.toml; a file is used as it is.
std::string profilePath(const std::string& nameOrPath, const std::string& sourceDir);
// loadProfile(profilePath(nameOrPath, sourceDir)).
Profile loadNamedProfile(const std::string& nameOrPath, const std::string& sourceDir);

}  // namespace pst
