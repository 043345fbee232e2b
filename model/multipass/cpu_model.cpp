// Bit-accurate CPU model of the multipass noise passes; see cpu_model.h.
#include "cpu_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pst::multipass {

namespace {

// Float -> UNORM (GL fixed-point conversion): round(clamp(x) M), tracking the tie margin.
uint32_t toUnorm(double x, double M, Stats& stats) {
    const double c = std::clamp(x, 0.0, 1.0) * M;
    if (x > 0.0 && x < 1.0) {
        const double frac = c - std::floor(c);
        stats.minTieMargin = std::min(stats.minTieMargin, std::fabs(frac - 0.5));
    }
    return static_cast<uint32_t>(std::floor(c + 0.5));
}

// round(d s / M) in integers: floor((2 d s + M) / 2M); d s / M is never a tie (M odd).
uint32_t mulUnorm(int64_t d, int64_t s, int64_t M) { return static_cast<uint32_t>((2 * d * s + M) / (2 * M)); }

}  // namespace

Image8 runCpu(const Program& prog, const Tables& tables, const Image8& s, const Image8& t,
              const Image8& r, Stats* statsOut, State* stateOut) {
    if (s.width != t.width || s.width != r.width || s.height != t.height || s.height != r.height ||
        s.px.size() != size_t(s.width) * s.height || t.px.size() != s.px.size() ||
        r.px.size() != s.px.size())
        throw std::invalid_argument("multipass: s, t, r images differ in size");
    State local;
    State& st = stateOut ? *stateOut : local;
    for (Image8& im : st.img) im = Image8{s.width, s.height, std::vector<uint32_t>(s.px.size(), 0)};
    const int64_t M = (int64_t(1) << prog.b) - 1;
    st.img[TexS] = s;
    st.img[TexT] = t;
    st.img[TexR] = r;
    Stats stats;
    const size_t n = s.px.size();
    for (const Pass& p : prog.passes) {
        std::vector<uint32_t>& dst = st.img[p.dst].px;
        const std::vector<uint32_t>& src = st.img[p.src].px;
        switch (p.op) {
            case Op::Transfer:
                for (size_t i = 0; i < n; ++i) {
                    uint32_t v = toUnorm(src[i] / double(M) * p.scale + p.bias, double(M), stats);
                    // PixelMap: a 2^b-entry map indexed by round(c M), the value just stored
                    if (p.table != NoTable) v = tables[p.table][v];
                    dst[i] = v;
                }
                break;
            case Op::BlendAdd:
                for (size_t i = 0; i < n; ++i) dst[i] = uint32_t(std::min<int64_t>(M, int64_t(dst[i]) + src[i]));
                break;
            case Op::BlendSub:
                for (size_t i = 0; i < n; ++i) dst[i] = uint32_t(std::max<int64_t>(0, int64_t(src[i]) - dst[i]));
                break;
            case Op::BlendMul:
                for (size_t i = 0; i < n; ++i) dst[i] = mulUnorm(dst[i], src[i], M);
                break;
            case Op::BlendMulInv:
                for (size_t i = 0; i < n; ++i) dst[i] = mulUnorm(dst[i], M - src[i], M);
                break;
            case Op::BlendXor:
                for (size_t i = 0; i < n; ++i) dst[i] = dst[i] ^ src[i];
                break;
            case Op::Save:
                std::swap(st.img[p.dst].px, st.img[p.src].px);
                break;
            case Op::Clear:
                std::fill(dst.begin(), dst.end(), uint32_t(p.k0));
                break;
            case Op::RcShiftLeft: {
                std::vector<uint32_t> out(n);  // dst may be src (5.3 shifts tex_corrnan in place)
                for (size_t i = 0; i < n; ++i) out[i] = uint8_t(rc::shiftLeft(src[i]));
                dst.swap(out);
                break;
            }
            case Op::RcIncWrap:
                for (size_t i = 0; i < n; ++i) dst[i] = uint8_t(rc::incWrap(src[i], p.k0, p.k1));
                break;
            case Op::RcBlendHiBit:
                for (size_t i = 0; i < n; ++i) dst[i] = uint8_t(rc::blendHiBit(src[i], dst[i], p.k0, p.k1, p.alpha));
                break;
        }
    }
    if (statsOut) *statsOut = stats;
    return st.img[TexNoise];
}

uint8_t toFixed(double x, const Format& f) {
    if (!std::isfinite(x)) return 0;
    const double v = std::floor(x * (1 << f.bf));
    return static_cast<uint8_t>(static_cast<int64_t>(std::fmod(v, 256.0) + 256.0) & 255);
}

}  // namespace pst::multipass
