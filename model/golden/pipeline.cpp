#include "pipeline.h"

#include <sstream>

#include "arith_fx.h"
#include "clut_filter_fx.h"
#include "contract.h"
#include "fixed.h"
#include "noise_fx.h"
#include "subband_fx.h"
#include "worley_fx.h"

namespace pst {

const char* toString(Unit u) {
    switch (u) {
        case Unit::Transform: return "octave transform (lattice index, fraction)";
        case Unit::Noise: return "noise (value, gradient)";
        case Unit::Quadric: return "quadric (q, grad q)";
        case Unit::Accumulate: return "octave accumulation (f, grad f)";
        case Unit::FilterWidth: return "filter width (W)";
        case Unit::ClutFilter: return "colour-table filter (RGBA)";
        default: return "none";
    }
}

GoldenPipeline::GoldenPipeline(const Profile& profile)
    : profile_(profile), oct_(profile.octaves), clut_(std::make_unique<ClutFilterFx>(profile)) {}
GoldenPipeline::~GoldenPipeline() = default;
GoldenPipeline::GoldenPipeline(const GoldenPipeline& o)
    : profile_(o.profile_), fault_(o.fault_), ctrl_(o.ctrl_), active_(o.active_), wcap_(o.wcap_), oct_(o.oct_),
      clut_(std::make_unique<ClutFilterFx>(*o.clut_)) {
    std::copy(std::begin(o.quad_), std::end(o.quad_), quad_);
    std::copy(std::begin(o.worley_), std::end(o.worley_), worley_);
    std::copy(std::begin(o.fade_), std::end(o.fade_), fade_);
}
GoldenPipeline& GoldenPipeline::operator=(const GoldenPipeline& o) {
    if (this != &o) *this = GoldenPipeline(o);
    return *this;
}

// Register map of docs/HARDWARE.md (contract.h); signed fields are the low bits of the word,
// sign-extended.
void GoldenPipeline::write(uint16_t addr, uint32_t data) {
    namespace c = contract;
    const Profile& p = profile_;
    if (addr == c::kRegControl) {
        ctrl_ = data & ((1u << c::kRegControlBits) - 1);  // [0] clamp, [2:1] filter kind, [3] bandlimit
        if (!p.bandlimit()) ctrl_ &= ~(1u << c::kRegControlBandlimitLsb);  // no fade unit: the bit is not kept
    } else if (addr == c::kRegActive) {
        active_ = int(fx::wrapUnsigned(data, c::octave_count_bits(p.octaves)));  // as many bits as the RTL
    } else if (addr == c::kRegWcap) {
        if (p.widthCap()) wcap_ = int64_t(fx::wrapUnsigned(data, p.widthBits()));  // W's format
    } else if (addr >= c::kRegQuadric && addr < c::kRegQuadric + c::kRegQuadricCount) {
        quad_[addr - c::kRegQuadric] = fx::wrapSigned(data, p.quadric.width());
    } else if (addr >= c::kRegWorley && addr < c::kRegWorley + c::kRegWorleyCount) {
        worley_[addr - c::kRegWorley] = fx::wrapSigned(data, c::kWorleyCoefInt + c::kWorleyCoefFrac);
    } else if (addr >= c::kRegFade && addr < c::kRegFade + c::kRegFadeCount) {
        if (p.bandlimit()) fade_[addr - c::kRegFade] = int64_t(fx::wrapUnsigned(data, c::kFadeBits));
    } else if (addr >= c::kRegOctave && addr < c::kRegOctave + c::kRegOctaveStride * p.octaves) {
        Octave& o = oct_[(addr - c::kRegOctave) / c::kRegOctaveStride];
        const int k = (addr - c::kRegOctave) % c::kRegOctaveStride;
        if (k >= c::kRegOctaveM && k < c::kRegOctaveM + c::kRegOctaveMCount)
            o.m[k - c::kRegOctaveM] = fx::wrapSigned(data, p.matrix.width());
        else if (k >= c::kRegOctaveO && k < c::kRegOctaveO + c::kRegOctaveOCount)
            o.o[k - c::kRegOctaveO] = fx::wrapSigned(data, p.offset.width());
        else if (k == c::kRegOctaveA)
            o.a = fx::wrapSigned(data, p.amplitude.width());
        else if (k >= c::kRegOctaveGm && k < c::kRegOctaveGm + c::kRegOctaveGmCount)
            o.gm[k - c::kRegOctaveGm] = fx::wrapSigned(data, p.gradMatrix.width());
        else if (k == c::kRegOctaveLgm && p.bandlimit())
            o.lgm = fx::wrapSigned(data, c::kFadeLgBits);
        else if (k == c::kRegOctaveFm && p.bandlimit())
            o.fm = fx::wrapSigned(data, p.f.width());
    }
    clut_->write(addr, data);  // decodes the table ranges itself
}

PixelFx GoldenPipeline::eval(const FragmentFx& fr, UnitTrace* trace) const {
    const Profile& p = profile_;
    UnitTrace local;
    UnitTrace& t = trace ? *trace : local;
    t = UnitTrace();
    t.octaves = std::min(active_, p.octaves);
    auto bump = [&](Unit s) { return fault_ == s ? 1 : 0; };

    // Unit 3: quadric (independent of the octaves).
    quadricFx(p, fr.s, quad_, &t.q, t.gradq);
    t.q = fx::wrapSigned(t.q + bump(Unit::Quadric), p.f.width());

    // Units 1, 2, 4: per octave transform, noise, term; then the accumulation.
    fx::i128 fsum = t.q;
    fx::i128 gsum[3] = {t.gradq[0], t.gradq[1], t.gradq[2]};
    // Bandlimited octaves: the footprint's two edges' lg lengths, once per pixel.
    const bool fade = p.bandlimit() && ((ctrl_ >> contract::kRegControlBandlimitLsb) & 1u);
    t.lgx = fadeLgFx(p, fr.j);
    t.lgy = fadeLgFx(p, fr.j + 3);
    // The subband unit's filter (noise.subband_orientations 4, 8): the pixel's lg edges along the
    // orientations, per octave the weights from the fade table, which then does not fade the term.
    const bool aniso = p.noise.basis == NoiseBasis::Subband && subbandOrientations(p) != 0;
    int64_t sbLg[16] = {};
    if (aniso) subbandPixelLgFx(p, fr.j, sbLg);
    for (int i = 0; i < t.octaves; ++i) {
        const Octave& o = oct_[i];
        octaveTransformFx(p, fr.s, o.m, o.o, t.lat[i], t.frac[i]);
        if (i == 0 && fault_ == Unit::Transform)
            t.frac[i][0] = int64_t(fx::wrapUnsigned(t.frac[i][0] + 1, p.noiseLatticeFrac));
        if (p.noise.basis == NoiseBasis::Worley)
            worleyFx(p, t.lat[i], t.frac[i], worley_, &t.n[i], t.g[i]);
        else if (p.noise.basis == NoiseBasis::Subband) {
            int64_t lambda[8];
            for (int64_t& l : lambda) l = int64_t(1) << contract::kFadeFrac;
            if (aniso && fade) subbandLambdaFx(p, sbLg, o.lgm, fade_, lambda);
            subbandFx(p, t.lat[i], t.frac[i], lambda, &t.n[i], t.g[i]);
        }
        else
            noiseFx(p, t.lat[i], t.frac[i], &t.n[i], t.g[i]);
        if (i == 0) t.n[i] += bump(Unit::Noise);
        octaveTermFx(p, t.n[i], t.g[i], o.a, o.gm, &t.fterm[i], t.gterm[i]);
        t.alpha[i] = fade && !aniso ? octaveFadeFx(t.lgx, t.lgy, o.lgm, fade_) : int64_t(1) << contract::kFadeFrac;
        t.fterm[i] = fadeToMeanFx(p, t.fterm[i], o.fm, t.alpha[i]);
        for (int k = 0; k < 3; ++k) t.gterm[i][k] = fadeScaleFx(t.gterm[i][k], t.alpha[i]);
        fsum += t.fterm[i];
        for (int k = 0; k < 3; ++k) gsum[k] += t.gterm[i][k];
    }
    t.f = fx::satSigned(fsum, p.f.width());
    if (fault_ == Unit::Accumulate) t.f = fx::wrapSigned(t.f + 1, p.f.width());
    for (int k = 0; k < 3; ++k) t.grad[k] = fx::satSigned(gsum[k], p.grad.width());

    // Unit 5: filter width.
    t.w = filterWidthFx(p, t.grad, fr.j);
    // The width cap (filter.width_cap): W = min(W, wcap), after the norm (pst_width_stage).
    if (p.widthCap()) t.w = widthCapFx(p, t.w, wcap_);
    if (fault_ == Unit::FilterWidth) t.w = int64_t(fx::wrapUnsigned(t.w + 1, p.widthBits()));

    // Unit 6: colour-table filter.
    t.rgba = clut_->filter(t.f, t.w, (ctrl_ & 1u) != 0, int((ctrl_ >> 1) & 3u));
    if (fault_ == Unit::ClutFilter) t.rgba ^= 1u;

    PixelFx px;
    px.tag = fr.tag;
    px.rgba = t.rgba;
    px.f = t.f;
    for (int k = 0; k < 3; ++k) px.grad[k] = t.grad[k];
    px.w = t.w;
    return px;
}

std::string UnitTrace::describe(const Profile& p) const {
    std::ostringstream os;
    for (int i = 0; i < octaves; ++i) {
        os << "  octave " << i << ": lattice (" << lat[i][0] << ", " << lat[i][1] << ", " << lat[i][2]
           << ") frac (" << frac[i][0] << ", " << frac[i][1] << ", " << frac[i][2] << ")  n " << n[i]
           << " (" << fx::toDouble(n[i], p.noiseOutFrac) << ")  g (" << g[i][0] << ", " << g[i][1] << ", "
           << g[i][2] << ")  alpha " << alpha[i] << "  fterm " << fterm[i] << "\n";
    }
    os << "  quadric: q " << q << " (" << fx::toDouble(q, p.f.fracBits) << ")  grad q (" << gradq[0]
       << ", " << gradq[1] << ", " << gradq[2] << ")\n";
    os << "  accumulate: f " << f << " (" << fx::toDouble(f, p.f.fracBits) << ")  grad (" << grad[0]
       << ", " << grad[1] << ", " << grad[2] << ")\n";
    os << "  filter width: W " << w << " (" << fx::toDouble(w, p.widthFrac) << " entries)\n";
    char buf[64];
    std::snprintf(buf, sizeof buf, "0x%08x", rgba);
    os << "  colour-table filter: RGBA " << buf << "\n";
    return os.str();
}

bool operator==(const PixelFx& a, const PixelFx& b) {
    return a.tag == b.tag && a.rgba == b.rgba && a.f == b.f && a.grad[0] == b.grad[0] &&
           a.grad[1] == b.grad[1] && a.grad[2] == b.grad[2] && a.w == b.w;
}

}  // namespace pst
