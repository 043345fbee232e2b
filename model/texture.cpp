// The texture function (paper eq. 1, 3-4) and its filter width (section 3.2, eq. 10-12).
#include "texture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "subband.h"

namespace pst {

glm::dmat4 Quadric::matrix() const {
    // Eq. 4; symmetric, so GLM's column-major layout reads the same.
    return glm::dmat4(A, B, C, D,  //
                      B, E, F, G,  //
                      C, F, H, I,  //
                      D, G, I, J);
}

double Quadric::value(const glm::dvec3& s) const {
    // Eq. 3.
    const double x = s.x, y = s.y, z = s.z;
    return A * x * x + 2 * B * x * y + 2 * C * x * z + 2 * D * x + E * y * y + 2 * F * y * z +
           2 * G * y + H * z * z + 2 * I * z + J;
}

glm::dvec3 Quadric::gradient(const glm::dvec3& s) const {
    // 2 (Q [s 1])_xyz: eq. 11 with the linear terms D, G, I kept (DESIGN.md section 3).
    return 2.0 * glm::dvec3(A * s.x + B * s.y + C * s.z + D,  //
                            B * s.x + E * s.y + F * s.z + G,  //
                            C * s.x + F * s.y + H * s.z + I);
}

bool parseGradNorm(const std::string& name, GradNorm* out) { return contract::fromName(name, out); }

const char* toString(GradNorm v) { return contract::name(v); }

double evalF(const Texture& tex, const glm::dvec3& s, glm::dvec3* gradS) {
    // Eq. 1: f = q(s) + sum_i a_i n(M_i s + o_i);
    // eq. 10, 12: grad_s f = grad q + sum_i a_i M_i^T grad n.
    double f = tex.quadric.value(s);
    glm::dvec3 g = gradS ? tex.quadric.gradient(s) : glm::dvec3(0.0);
    for (const Octave& o : tex.octaves) {
        glm::dvec3 gn;
        f += o.amplitude * noise(o.M * s + o.offset, tex.noise, gradS ? &gn : nullptr);
        if (gradS) g += o.amplitude * (glm::transpose(o.M) * gn);
    }
    if (gradS) *gradS = g;
    return f;
}

bool parseBandlimit(const std::string& name, Bandlimit* out) {
    if (name == "off") *out = Bandlimit::Off;
    else if (name == "footprint") *out = Bandlimit::Footprint;
    else if (name == "isotropic") *out = Bandlimit::Isotropic;
    else if (name == "anisotropic") *out = Bandlimit::Anisotropic;
    else return false;
    return true;
}

std::string bandlimitUnsupported(const Texture& tex, Bandlimit b) {
    if (b == Bandlimit::Anisotropic && tex.noise.basis != NoiseBasis::Subband)
        return std::string("anisotropic filtering needs basis subband (the texture's basis is ") +
               toString(tex.noise.basis) + ")";
    return "";
}

const char* toString(Bandlimit v) {
    switch (v) {
    case Bandlimit::Off: return "off";
    case Bandlimit::Footprint: return "footprint";
    case Bandlimit::Isotropic: return "isotropic";
    case Bandlimit::Anisotropic: return "anisotropic";
    }
    return "?";
}

namespace {
// The key of a basis's caches: every noise option its values depend on.
std::string basisKey(const NoiseOptions& opt) {
    std::ostringstream key;
    key << toString(opt.basis) << ' ' << toString(opt.interp) << ' ' << toString(opt.corner) << ' '
        << toString(opt.hash) << ' ' << toString(opt.metric) << ' ' << opt.coef[0] << ' ' << opt.coef[1] << ' '
        << opt.coef[2] << ' ' << opt.coef[3] << ' ' << opt.cell;
    if (opt.basis == NoiseBasis::Subband)
        key << ' ' << opt.orientations << ' ' << opt.tileSize << ' ' << opt.seed << ' ' << toString(opt.param);
    return key.str();
}
}  // namespace

NoiseMoments noiseMoments(const NoiseOptions& opt) {
    static std::mutex mu;
    static std::map<std::string, NoiseMoments> cache;
    const std::string key = basisKey(opt);
    std::lock_guard<std::mutex> lock(mu);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    // 65536 points of the R3 low-discrepancy sequence over a 64-cell cube.
    const double g = 1.2207440846057596, a1 = 1 / g, a2 = 1 / (g * g), a3 = 1 / (g * g * g);
    double sum = 0, sum2 = 0;
    const int n = 65536;
    for (int i = 1; i <= n; ++i) {
        const glm::dvec3 p(std::fmod(0.5 + a1 * i, 1.0), std::fmod(0.5 + a2 * i, 1.0), std::fmod(0.5 + a3 * i, 1.0));
        const double v = noise(64.0 * p, opt);
        sum += v;
        sum2 += v * v;
    }
    NoiseMoments m;
    m.mean = sum / n;
    m.sd = std::sqrt(std::max(0.0, sum2 / n - m.mean * m.mean));
    cache[key] = m;
    return m;
}

namespace {
constexpr int kGainSteps = 4;                     // per octave of nu
// nu = 2^(k / 4), 1/16 .. 16 cells; beyond, c / nu (g(nu) nu is within 12 % of constant from 16 to
// 256 cells, measured with the table run to 256, which cost 5x the time).
constexpr int kGainLo = -4 * kGainSteps, kGainHi = 4 * kGainSteps;
}  // namespace

double noiseBoxGain(const NoiseOptions& opt, double nu) {
    static std::mutex mu;
    static std::map<std::string, std::vector<double>> cache;
    if (!(nu > 0.0)) return 1.0;
    std::vector<double> table;
    {
        std::lock_guard<std::mutex> lock(mu);
        auto it = cache.find(basisKey(opt));
        if (it != cache.end()) table = it->second;
    }
    if (table.empty()) {
        // Segments from the R3 low-discrepancy sequence (start in a 64-cell cube, direction on the
        // sphere); the mean of each by the midpoint rule at 8 points per cell (>= 16). The ratio is
        // taken over the same segments (the variance of their means over that of their centres'
        // values), so the sampling error of the two cancels to first order.
        const NoiseMoments m = noiseMoments(opt);
        const double g = 1.2207440846057596, a1 = 1 / g, a2 = 1 / (g * g), a3 = 1 / (g * g * g);
        const int segments = 1024;
        for (int k = kGainLo; k <= kGainHi; ++k) {
            const double len = std::exp2(double(k) / kGainSteps);
            const int q = std::max(16, int(std::ceil(8 * len)));  // <= 128
            double sum2 = 0, point2 = 0;
            for (int i = 1; i <= segments; ++i) {
                const double u1 = std::fmod(0.5 + a1 * i, 1.0), u2 = std::fmod(0.5 + a2 * i, 1.0),
                             u3 = std::fmod(0.5 + a3 * i, 1.0);
                const double z = 2 * u3 - 1, phi = 2 * 3.141592653589793 * std::fmod(u1 + u2, 1.0);
                const double rxy = std::sqrt(std::max(0.0, 1 - z * z));
                const glm::dvec3 d(rxy * std::cos(phi), rxy * std::sin(phi), z), p0 = 64.0 * glm::dvec3(u1, u2, u3);
                double mean = 0;
                for (int j = 0; j < q; ++j) mean += noise(p0 + ((j + 0.5) / q) * len * d, opt);
                mean = mean / q - m.mean;
                const double centre = noise(p0 + 0.5 * len * d, opt) - m.mean;
                sum2 += mean * mean;
                point2 += centre * centre;
            }
            table.push_back(point2 > 0 ? std::min(1.0, sum2 / point2) : 1.0);
        }
        std::lock_guard<std::mutex> lock(mu);
        cache[basisKey(opt)] = table;
    }
    const double x = std::log2(nu) * kGainSteps - kGainLo;
    if (x <= 0) return 1.0;  // below 1/16 cell: as good as a point (table[0] is close to 1)
    const int n = int(table.size()) - 1;
    if (x >= n) return table[n] * std::exp2(double(kGainHi) / kGainSteps) / nu;  // c / nu beyond
    const int i = int(std::floor(x));
    const double t = x - i;
    return table[i] * (1 - t) + table[i + 1] * t;
}

double spectralNorm(const glm::dmat3& M) {
    // Power iteration on M^T M from each axis (the largest Rayleigh quotient wins).
    const glm::dmat3 A = glm::transpose(M) * M;
    double best = 0;
    for (int k = 0; k < 3; ++k) {
        glm::dvec3 v(0.0);
        v[k] = 1;
        for (int it = 0; it < 100; ++it) {
            const glm::dvec3 w = A * v;
            const double l = glm::length(w);
            if (!(l > 0)) break;
            v = w / l;
        }
        best = std::max(best, glm::dot(v, A * v));
    }
    return std::sqrt(best);
}

double footprintNorm(const glm::dvec3& v) {
    const double a = std::abs(v.x), b = std::abs(v.y), c = std::abs(v.z);
    const double mx = std::max({a, b, c});
    return mx + 0.375 * (a + b + c - mx);
}

double octaveIsotropic(const Octave& o, const NoiseOptions& opt, const glm::dvec3& dsdx, const glm::dvec3& dsdy) {
    const double m = spectralNorm(o.M);
    auto h = [&](const glm::dvec3& e) {
        const double nu = std::clamp(m * footprintNorm(e), std::exp2(kIsoLgLo), std::exp2(kIsoLgHi));
        return std::sqrt(noiseBoxGain(opt, nu));
    };
    return h(dsdx) * h(dsdy);
}

double octaveFootprint(const Octave& o, const NoiseOptions& opt, const glm::dvec3& s, const glm::dvec3& dsdx,
                       const glm::dvec3& dsdy, glm::dvec3* grad, double* keptVar) {
    const NoiseMoments m = noiseMoments(opt);
    const double nx = glm::length(o.M * dsdx), ny = glm::length(o.M * dsdy);
    const double nMaj = std::max(nx, ny), nMin = std::min(nx, ny);
    const glm::dvec3& dMaj = nx >= ny ? dsdx : dsdy;
    const int K = int(std::clamp(std::ceil(2.0 * nMaj), 1.0, double(kFootprintSamples)));
    double v = 0;
    glm::dvec3 gv(0.0);
    for (int k = 0; k < K; ++k) {
        glm::dvec3 gn;
        v += noise(o.M * (s + ((k + 0.5) / K - 0.5) * dMaj) + o.offset, opt, grad ? &gn : nullptr);
        if (grad) gv += gn;
    }
    v /= K;
    const double gMaj = noiseBoxGain(opt, nMaj), gMin = noiseBoxGain(opt, nMin);
    const double gK = K >= 2.0 * nMaj ? gMaj : std::max(gMaj, 1.0 / K);
    const double w = std::sqrt(gMin) * std::sqrt(gK > 0 ? gMaj / gK : 1.0);
    if (grad) *grad = w * (glm::transpose(o.M) * (gv / double(K)));
    if (keptVar) *keptVar = gMaj * gMin;
    return m.mean + w * (v - m.mean);
}

double evalFBandlimited(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                        const glm::dvec3& dsdy, glm::dvec3* gradS, double* fadedSd) {
    const NoiseMoments m = noiseMoments(tex.noise);
    double f = tex.quadric.value(s), var = 0;
    glm::dvec3 g = gradS ? tex.quadric.gradient(s) : glm::dvec3(0.0);
    const bool subband = tex.noise.basis == NoiseBasis::Subband &&
                         (tex.bandlimit == Bandlimit::Isotropic || tex.bandlimit == Bandlimit::Anisotropic);
    if (tex.bandlimit == Bandlimit::Anisotropic && !subband)
        throw std::invalid_argument("evalFBandlimited: " + bandlimitUnsupported(tex, tex.bandlimit));
    for (const Octave& o : tex.octaves) {
        if (subband) {
            // Eq. 7 per octave: the subband weights from the footprint in the octave's space.
            const SubbandFilterKind kind = tex.bandlimit == Bandlimit::Anisotropic ? SubbandFilterKind::Anisotropic
                                                                                   : SubbandFilterKind::Isotropic;
            glm::dvec3 gn;
            double kept = 1;
            f += o.amplitude * subbandNoise(o.M * s + o.offset, tex.noise, kind, o.M * dsdx, o.M * dsdy,
                                            gradS ? &gn : nullptr, &kept);
            if (gradS) g += o.amplitude * (glm::transpose(o.M) * gn);
            // What the filter removed widens the colour-table filter, as for footprint.
            var += std::pow(o.amplitude * m.sd, 2) * std::max(0.0, 1.0 - kept);
            continue;
        }
        if (tex.bandlimit == Bandlimit::Footprint) {
            glm::dvec3 gt;
            double kept = 1;
            f += o.amplitude * octaveFootprint(o, tex.noise, s, dsdx, dsdy, gradS ? &gt : nullptr, &kept);
            if (gradS) g += o.amplitude * gt;
            var += std::pow(o.amplitude * m.sd, 2) * (1.0 - kept);
            continue;
        }
        // Isotropic: the term faded toward its mean by alpha, its gradient toward 0 (off: the
        // point sample). A basis whose mean is not 0 (worley) keeps its mean as the octave fades.
        const double alpha = tex.bandlimit == Bandlimit::Isotropic ? octaveIsotropic(o, tex.noise, dsdx, dsdy) : 1.0;
        const double a = o.amplitude * alpha;
        glm::dvec3 gn;
        f += a * noise(o.M * s + o.offset, tex.noise, gradS ? &gn : nullptr) + o.amplitude * (1.0 - alpha) * m.mean;
        if (gradS) g += a * (glm::transpose(o.M) * gn);
    }
    if (gradS) *gradS = g;
    if (fadedSd) *fadedSd = std::sqrt(var);
    return f;
}

bool bandlimitWidens(const Texture& tex) {
    return tex.bandlimit == Bandlimit::Footprint || tex.bandlimit == Bandlimit::Anisotropic ||
           (tex.bandlimit == Bandlimit::Isotropic && tex.noise.basis == NoiseBasis::Subband);
}

double bandlimitedWidth(const Texture& tex, const glm::dvec3& gradS, const glm::dvec3& dsdx,
                        const glm::dvec3& dsdy, double fadedSd) {
    const double w = filterWidth(gradS, dsdx, dsdy, tex.norm);
    const bool widen = bandlimitWidens(tex);
    return widen ? std::sqrt(w * w + 12.0 * fadedSd * fadedSd) : w;
}

bool quadricVaries(const Quadric& q) {
    return q.A != 0 || q.B != 0 || q.C != 0 || q.D != 0 || q.E != 0 || q.F != 0 || q.G != 0 || q.H != 0 || q.I != 0;
}

double widthCapOf(const Texture& tex, int octaves) {
    if (quadricVaries(tex.quadric)) return std::numeric_limits<double>::infinity();
    const size_t n = octaves < 0 ? tex.octaves.size() : std::min(tex.octaves.size(), size_t(octaves));
    double a2 = 0;
    for (size_t i = 0; i < n; ++i) a2 += tex.octaves[i].amplitude * tex.octaves[i].amplitude;
    return std::sqrt(12.0 * a2) * noiseMoments(tex.noise).sd;
}

void capWidth(const Texture& tex, double* w, glm::dvec2* wxy) {
    const double cap = widthCapOf(tex);
    if (!(*w > cap)) return;
    if (wxy) *wxy *= cap / *w;
    *w = cap;
}

double filterWidth(const glm::dvec3& gradS, const glm::dvec3& dsdx, const glm::dvec3& dsdy,
                   GradNorm norm) {
    // grad_x f = (grad_s f)^T ds/dx (section 3.2), then its norm.
    const double gx = std::abs(glm::dot(gradS, dsdx)), gy = std::abs(glm::dot(gradS, dsdy));
    switch (norm) {
    case GradNorm::Euclid: return std::sqrt(gx * gx + gy * gy);
    case GradNorm::MaxHalfMin: return std::max(gx, gy) + 0.5 * std::min(gx, gy);
    case GradNorm::L1: return gx + gy;
    }
    return 0.0;
}

glm::dvec2 footprintWidths(const glm::dvec3& gradS, const glm::dvec3& dsdx, const glm::dvec3& dsdy) {
    return glm::dvec2(std::abs(glm::dot(gradS, dsdx)), std::abs(glm::dot(gradS, dsdy)));
}

glm::dvec4 filterColour(const ColorMap& clut, double f, double w, const glm::dvec2& wxy, FilterKind kind) {
    if (kind != FilterKind::Trapezoid) return clut.filter(f, w, kind);
    if (!(wxy.x > 0.0 || wxy.y > 0.0)) return clut.filter(f, w, FilterKind::Box);
    return clut.filterTrapezoid(f, wxy.x, wxy.y);
}

glm::dvec2 bandlimitedFootprint(const Texture& tex, const glm::dvec2& wxy, double fadedSd) {
    const bool widen = bandlimitWidens(tex);
    if (!widen || !(fadedSd > 0.0)) return wxy;
    const double e2 = glm::dot(wxy, wxy), add = 12.0 * fadedSd * fadedSd;
    if (!(e2 > 0.0)) return glm::dvec2(std::sqrt(add), 0.0);
    return wxy * std::sqrt(1.0 + add / e2);
}

TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy) {
    return shade(tex, s, dsdx, dsdy, tex.filter);
}

TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy, FilterKind filter) {
    TextureSample r;
    double sd = 0;
    r.f = tex.bandlimit != Bandlimit::Off ? evalFBandlimited(tex, s, dsdx, dsdy, &r.gradS, &sd)
                                          : evalF(tex, s, &r.gradS);
    r.filterWidth = tex.bandlimit != Bandlimit::Off ? bandlimitedWidth(tex, r.gradS, dsdx, dsdy, sd)
                                                    : filterWidth(r.gradS, dsdx, dsdy, tex.norm);
    glm::dvec2 wxy = bandlimitedFootprint(tex, footprintWidths(r.gradS, dsdx, dsdy), sd);
    if (tex.widthCap) capWidth(tex, &r.filterWidth, &wxy);  // issue 44 part 2
    r.rgba = filterColour(tex.clut, r.f, r.filterWidth, wxy, filter);  // eq. 9
    return r;
}

}  // namespace pst
