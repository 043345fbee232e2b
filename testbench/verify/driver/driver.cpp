#include "driver.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

#include "clut_filter_fx.h"
#include "contract.h"
#include "fixed.h"
#include "input_error.h"

namespace pst {
namespace {

uint32_t word(int64_t v) { return uint32_t(uint64_t(v)); }  // low 32 bits, sign-extended in hardware

int64_t q(double v, const FixedFormat& f) { return fx::quantize(v, f.intBits, f.fracBits); }

}  // namespace

int64_t fadeLgNorm(const glm::dmat3& M) {
    namespace c = contract;
    const double m = spectralNorm(M);
    const int64_t lo = -(int64_t(1) << (c::kFadeLgBits - 1)), hi = -lo - 1;
    if (!(m > 0)) return lo;
    return std::clamp<int64_t>(std::llround(std::log2(m) * (1 << c::kFadeLgFrac)), lo, hi);
}

int64_t fadeTableEntry(const NoiseOptions& noise, int k) {
    namespace c = contract;
    static_assert(c::kFadeLgLo == -int(kIsoLgLo) && c::kFadeEntries == 4 * int(kIsoLgHi - kIsoLgLo),
                  "the reference's isotropic range is the fade table's");
    const double nu = std::exp2(-c::kFadeLgLo + (k + 0.5) / 4.0);
    const int64_t one = int64_t(1) << c::kFadeFrac;
    return std::min<int64_t>(one, std::llround(std::sqrt(noiseBoxGain(noise, nu)) * double(one)));
}

int64_t subbandWeightEntry(const NoiseOptions& noise, int k) {
    // h(nu) = exp(-sigma^2 pi^2 nu^2 / 2): eq. 4's Gaussian at the subband's centre frequency pi/16
    // per tile pixel, 16 tile pixels per noise unit (subband_fx.cpp), kSubbandWeightOffset above the
    // entry's centre.
    namespace c = contract;
    const double nu = std::exp2(-c::kFadeLgLo + (k + 0.5) / 4.0 + kSubbandWeightOffset), pi = 3.141592653589793;
    const double h = std::exp(-noise.sigma * noise.sigma * pi * pi * nu * nu / 2);
    return std::llround(h * double(int64_t(1) << c::kFadeFrac));
}

int hardwareFilterKind(FilterKind k) {
    using K = contract::FilterKind;
    switch (k) {
        case FilterKind::None: return int(K::None);
        case FilterKind::MipNearest: return int(K::Mip);
        case FilterKind::MipLinear: return int(K::MipBlended);
        case FilterKind::Sat:
        case FilterKind::Box:
        case FilterKind::Trapezoid: return int(K::Sat);
    }
    return int(K::Sat);
}

std::pair<uint16_t, uint32_t> controlWrite(const Texture& tex, int filterKind) {
    const uint32_t clamp = tex.clut.wrap() == WrapMode::Clamp ? 1u : 0u;
    // The bit enables the fade unit's table: the isotropic fade, or on a subband unit with its
    // filter (noise.subband_orientations) the anisotropic weights.
    const uint32_t fade = tex.bandlimit == Bandlimit::Isotropic || tex.bandlimit == Bandlimit::Anisotropic ? 1u : 0u;
    return {contract::kRegControl, (clamp << contract::kRegControlClampLsb) |
                                       (uint32_t(filterKind) << contract::kRegControlKindLsb) |
                                       (fade << contract::kRegControlBandlimitLsb)};
}

std::string refusedFilter(const Profile& p, const Texture& tex) {
    // Issue 44 part 2, chosen on the fly-ins' training set (scripts/flyins.py --split training;
    // docs/HARDWARE.md unit 6 "Refused combinations"): the colour-table MIP map (nearest or
    // blended) on a ramp colour map, on the bases whose gradient overstates f's spread in a pixel
    // (worley, and subband without its anisotropic filter). The MIP box is aligned to its
    // level's blocks, not centred on f; on a ramp the point sample is already the box average where
    // f is linear in the pixel, so the misplaced box only adds error.
    if (tex.filter != FilterKind::MipNearest && tex.filter != FilterKind::MipLinear) return "";
    if (!tex.clutRamp) return "";
    const NoiseBasis b = p.noise.basis;
    if (b != NoiseBasis::Worley && b != NoiseBasis::Subband) return "";
    if (b == NoiseBasis::Subband && p.noiseSubbandOrientations != 0 && tex.bandlimit == Bandlimit::Anisotropic)
        return "";
    const std::string where =
        tex.clutInterpSource.empty() ? "texture '" + tex.name + "': colormap.interp" : tex.clutInterpSource;
    return where + ": 'linear' (a ramp) with filter '" + toString(tex.filter) + "' is refused on profile '" + p.name +
           "' (basis " + toString(b) +
           (b == NoiseBasis::Subband ? ", its anisotropic filter off" : "") +
           "): the colour-table MIP map's box sits on its level's blocks, not centred on f, and on a ramp it "
           "measured worse than unfiltered (RMS against the truth; docs/HARDWARE.md unit 6, refused combinations); "
           "use filter sat or none, or a step colour map (interp = \"step\")";
}

std::string hardwareUnsupported(const Profile& p, const Texture& tex) {
    // A subband unit with its anisotropic filter (noise.subband_orientations): the table is the
    // filter's weights, so bandlimit is anisotropic or off.
    const bool sbFilter = p.noise.basis == NoiseBasis::Subband && p.noiseSubbandOrientations != 0;
    // "FILE:LINE: textures.NAME.bandlimit" when the scene gave it.
    const std::string bl = tex.bandlimitSource.empty() ? "texture '" + tex.name + "': bandlimit" : tex.bandlimitSource;
    if (sbFilter && tex.noise.basis == NoiseBasis::Subband) {
        if (tex.bandlimit != Bandlimit::Off && tex.bandlimit != Bandlimit::Anisotropic)
            return bl + ": '" + toString(tex.bandlimit) + "'; the subband unit of profile '" +
                   p.name + "' filters with its anisotropic weights (write \"anisotropic\" or \"off\")";
    } else if (tex.bandlimit == Bandlimit::Isotropic && !p.bandlimit())
        return bl + ": profile '" + p.name +
               "' has no fade unit (filter.bandlimit = \"off\"); use a profile with filter.bandlimit = \"isotropic\" "
               "(e.g. sim/test_profiles/reduced_bandlimit.toml) or render it without --profile";
    else if (tex.bandlimit != Bandlimit::Off && tex.bandlimit != Bandlimit::Isotropic)
        return bl + ": '" + toString(tex.bandlimit) +
               "' is in the reference model only (the hardware's is 'isotropic'); render it without --profile";
    // The profile's noise unit computes one basis (hardwareBasis of its interp / corner / hash).
    if (tex.noise.basis != p.noise.basis) {
        const std::string where =
            tex.basisSource.empty() ? "texture '" + tex.name + "': noise.basis" : tex.basisSource;
        const std::string how = tex.noise.basis == NoiseBasis::Worley || tex.noise.basis == NoiseBasis::Subband
                                    ? "render it with the reference model (no --profile)"
                                    : std::string("render it with a profile of basis ") + toString(tex.noise.basis) +
                                          " or with the reference model (no --profile)";
        return where + ": basis '" + toString(tex.noise.basis) + "' has no hardware unit in profile '" + p.name +
               "' (its noise unit computes '" + toString(p.noise.basis) + "'); " + how;
    }
    // "FILE:LINE: textures.NAME.noise." (the noise table's line) when the scene named it.
    const NoiseOptions& n = tex.noise;
    const std::string& src = tex.basisSource;
    const std::string where = src.size() > 5 && src.compare(src.size() - 5, 5, "basis") == 0
                                  ? src.substr(0, src.size() - 5)
                                  : "texture '" + tex.name + "': noise.";
    const std::string prof = "profile '" + p.name + "'";
    if (p.noise.basis == NoiseBasis::Worley) {
        // The worley unit computes one variant (rtl/noise/pst_worley.sv): the scene must ask for it,
        // so that its reference is the variant the hardware computes.
        if (n.search != p.noise.search || n.maxPoints != p.noise.maxPoints || n.cubes != WorleyCubes::Rom256)
            return where + "search/max_points/cubes: " + toString(n.search) + ", " + std::to_string(n.maxPoints) + ", " +
                   toString(n.cubes) + "; the worley unit of " + prof + " computes " + toString(p.noise.search) +
                   ", " + std::to_string(p.noise.maxPoints) + ", rom256 (write these in the scene)";
        if (n.metric != WorleyMetric::Euclid) return where + "metric: the worley unit of " + prof + " is euclid only";
        if (n.cell != 0.0) return where + "cell: the worley unit of " + prof + " has no cell term";
        const double cmax = double(1 << (contract::kWorleyCoefInt - 1));
        for (int k = 0; k < 4; ++k) {
            if (k >= p.noiseWorleyOrder && n.coef[k] != 0.0)
                return where + "coef: C" + std::to_string(k + 1) + " is not 0; the worley unit of " + prof +
                       " computes F1..F" + std::to_string(p.noiseWorleyOrder) + " (noise.worley_order)";
            if (!(std::abs(n.coef[k]) < cmax))
                return where + "coef: C" + std::to_string(k + 1) + " is outside the coefficient registers' range (-" +
                       std::to_string(int(cmax)) + ", " + std::to_string(int(cmax)) + ")";
        }
    }
    if (p.noise.basis == NoiseBasis::Subband) {
        // The subband unit samples one tile (rtl/noise/pst_subband.sv): the scene must ask for the
        // tiles its ROM is sampled from, on its plane, so that its reference is what the hardware
        // computes (the isotropic sum of a scale does not depend on the orientations).
        if (n.param != p.noise.param)
            return where + "param: '" + toString(n.param) + "'; the subband unit of " + prof + " samples the plane '" +
                   toString(p.noise.param) + "' (noise.subband)";
        if (n.tileSize != p.noise.tileSize || n.seed != p.noise.seed)
            return where + "tile_size/seed: " + std::to_string(n.tileSize) + ", " + std::to_string(n.seed) +
                   "; the subband unit of " + prof + " holds the tile of tile_size " + std::to_string(p.noise.tileSize) +
                   ", seed " + std::to_string(p.noise.seed) + " (write these in the scene)";
        if (p.noiseSubbandOrientations != 0 && n.orientations != p.noiseSubbandOrientations)
            return where + "orientations: " + std::to_string(n.orientations) + "; the subband unit of " + prof +
                   " holds " + std::to_string(p.noiseSubbandOrientations) + " oriented tiles";
        if (p.noiseSubbandOrientations != 0 && n.weights != SubbandWeights::Heuristic)
            return where + "weights: the subband unit of " + prof + " computes the heuristic weights";
    }
    if (std::string why = refusedFilter(p, tex); !why.empty()) return why;
    if (tex.widthCap && !p.widthCap())
        return (tex.widthCapSource.empty() ? "texture '" + tex.name + "': width_cap" : tex.widthCapSource) +
               ": profile '" + p.name + "' has no width-cap unit (filter.width_cap = \"off\"); use a profile with "
               "filter.width_cap = \"on\" (e.g. sim/test_profiles/reduced_worley.toml) or render it without --profile";
    if (tex.clut.size() != p.clutSize())
        return (tex.clutSource.empty() ? "texture '" + tex.name + "': colormap.size" : tex.clutSource) + ": " +
               std::to_string(tex.clut.size()) + " entries; profile '" + p.name + "' has a " +
               std::to_string(p.clutSize()) + "-entry colour table (pipeline.log2_clut = " + std::to_string(p.log2Clut) + ")";
    return "";
}

TextureProgram programTexture(const Profile& p, const Texture& tex) {
    if (std::string why = hardwareUnsupported(p, tex); !why.empty()) throw InputError(why);
    TextureProgram prog;
    std::ostringstream notes;
    prog.filterKind = hardwareFilterKind(tex.filter);
    if (tex.filter == FilterKind::Box) notes << "box filter done by the SAT; ";
    if (tex.filter == FilterKind::Trapezoid) notes << "trapezoid filter done by the SAT (no hardware unit); ";
    prog.writes.push_back(controlWrite(tex, prog.filterKind));

    // Quadric A..J (eq. 3).
    const Quadric& qd = tex.quadric;
    const double coef[10] = {qd.A, qd.B, qd.C, qd.D, qd.E, qd.F, qd.G, qd.H, qd.I, qd.J};
    static_assert(std::size(coef) == contract::kRegQuadricCount);
    for (int k = 0; k < contract::kRegQuadricCount; ++k)
        prog.writes.push_back({uint16_t(contract::kRegQuadric + k), word(q(coef[k], p.quadric))});

    // Octaves: M (row-major), o, a, GM = a M^T (row-major).
    prog.activeOctaves = std::min<int>(int(tex.octaves.size()), p.octaves);
    prog.droppedOctaves = int(tex.octaves.size()) - prog.activeOctaves;
    if (prog.droppedOctaves > 0)
        notes << prog.droppedOctaves << " of " << tex.octaves.size() << " octaves dropped (profile holds "
              << p.octaves << "); ";
    prog.writes.push_back({contract::kRegActive, uint32_t(prog.activeOctaves)});
    for (int i = 0; i < prog.activeOctaves; ++i) {
        const Octave& o = tex.octaves[i];
        const int base = contract::kRegOctave + contract::kRegOctaveStride * i;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                prog.writes.push_back({uint16_t(base + contract::kRegOctaveM + 3 * r + c), word(q(o.M[c][r], p.matrix))});
                // (a M^T)[r][c] = a M[c][r]
                prog.writes.push_back({uint16_t(base + contract::kRegOctaveGm + 3 * r + c),
                                       word(q(o.amplitude * o.M[r][c], p.gradMatrix))});
            }
        for (int k = 0; k < 3; ++k)
            prog.writes.push_back({uint16_t(base + contract::kRegOctaveO + k), word(q(o.offset[k], p.offset))});
        prog.writes.push_back({uint16_t(base + contract::kRegOctaveA), word(q(o.amplitude, p.amplitude))});
        if (p.bandlimit()) {
            prog.writes.push_back({uint16_t(base + contract::kRegOctaveLgm), word(fadeLgNorm(o.M))});
            // The term's mean a mean(n), where the fade takes the term (not 0: worley's mean is not 0).
            prog.writes.push_back({uint16_t(base + contract::kRegOctaveFm),
                                   word(q(o.amplitude * noiseMoments(tex.noise).mean, p.f))});
        }
    }
    if (p.bandlimit())
        for (int k = 0; k < contract::kFadeEntries; ++k)
            prog.writes.push_back({uint16_t(contract::kRegFade + k),
                                   uint32_t(p.noise.basis == NoiseBasis::Subband && p.noiseSubbandOrientations != 0
                                                ? subbandWeightEntry(tex.noise, k)
                                                : fadeTableEntry(tex.noise, k))});

    // The filter-width cap (issue 44 part 2; docs/HARDWARE.md unit 5).
    if (p.widthCap()) {
        const int64_t wcap = widthCapRegister(p, tex, prog.activeOctaves);
        prog.writes.push_back({contract::kRegWcap, word(wcap)});
        if (tex.widthCap && wcap == fx::maxUnsigned(p.widthBits()))
            notes << "width cap: none (" << (quadricVaries(tex.quadric) ? "the quadric varies" : "beyond W's range")
                  << "); ";
    }

    // The worley unit's coefficients C_k (n = sum C_k F_k).
    if (p.noise.basis == NoiseBasis::Worley)
        for (int k = 0; k < contract::kRegWorleyCount; ++k)
            prog.writes.push_back({uint16_t(contract::kRegWorley + k),
                                   word(fx::quantize(tex.noise.coef[size_t(k)], contract::kWorleyCoefInt,
                                                     contract::kWorleyCoefFrac))});

    // Colour tables, built here (driver side) and written through the register port.
    if (tex.clut.size() != p.clutSize()) {
        throw std::invalid_argument("texture '" + tex.name + "': colour map has " + std::to_string(tex.clut.size()) +
                                    " entries, profile '" + p.name + "' needs " + std::to_string(p.clutSize()));
    }
    const ClutTables tables = buildClutTables(p, tex.clut.entries());
    for (const auto& w : clutRegisterWrites(p, tables)) prog.writes.push_back(w);
    if (tex.noise.basis == NoiseBasis::Rayshade &&
        (tex.noise.interp != p.noise.interp || tex.noise.corner != p.noise.corner || tex.noise.hash != p.noise.hash))
        notes << "noise variant of the profile (" << toString(p.noise.interp) << ", " << toString(p.noise.corner) << ", "
              << toString(p.noise.hash) << "); ";
    if (tex.norm != p.filterNorm) notes << "|grad| by " << toString(p.filterNorm) << "; ";
    prog.notes = notes.str();
    return prog;
}

int64_t widthCapRegister(const Profile& p, const Texture& tex, int octaves) {
    const int64_t wmax = fx::maxUnsigned(p.widthBits());
    if (!tex.widthCap) return wmax;
    const double cap = widthCapOf(tex, octaves) * double(p.clutSize()) * std::exp2(p.widthFrac);
    if (!(cap < double(wmax))) return wmax;   // infinite (a varying quadric) or beyond W's range
    return int64_t(std::floor(cap));
}

FragmentFx quantizeFragment(const Profile& p, uint32_t tag, const glm::dvec3& s, const glm::dvec3& dsdx,
                            const glm::dvec3& dsdy) {
    FragmentFx f;
    f.tag = tag;
    for (int k = 0; k < 3; ++k) {
        f.s[k] = q(s[k], p.coord);
        f.j[k] = q(dsdx[k], p.jacobian);
        f.j[3 + k] = q(dsdy[k], p.jacobian);
    }
    return f;
}

glm::dvec4 unpackRgba(const Profile& p, uint32_t rgba) {
    const uint32_t mask = (1u << p.colourBits) - 1;
    glm::dvec4 c;
    for (int k = 0; k < 4; ++k) c[k] = double((rgba >> (k * p.colourBits)) & mask) / double(mask);
    return c;
}

}  // namespace pst
