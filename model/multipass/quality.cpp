// Quality measures of the multipass noise; see quality.h.
#include "quality.h"

#include <algorithm>
#include <cmath>

#include "cpu_model.h"

namespace pst::multipass {

int rcFirstStage(const Params& params, const RcConstants& c, int i, int j, int k) {
    const int bi = params.format.bi(), K[3] = {i, j, k};
    int acc = RcConstants::start;
    for (int kk = 0; kk < bi; ++kk)
        for (int a = 0; a < 3; ++a) {
            const int bit = K[a] >> (bi - 1 - kk) & 1;
            acc = rc::blendHiBit(bit ? 255 : 0, acc, c.ranzero[a][kk], c.ranone[a][kk], RcConstants::alpha);
        }
    return acc;
}

int latticeValue(const Params& params, const Tables& T, const RcConstants& c, int i, int j, int k) {
    if (params.variant == Variant::Sgi) return T[Nran][T[Sran][i] + T[Tran][j] + T[Rran][k]];
    if (params.variant == Variant::Xor) {
        const int off = 1000000 & 255;  // Rayshade's lattice offset, low 8 bits
        return T[ValuePerm][T[Perm][T[Perm][(i + off) & 255] ^ ((j + off) & 255)] ^ ((k + off) & 255)];
    }
    const int acc = rcFirstStage(params, c, i, j, k);
    int acc2 = RcConstants::start;
    for (int b = 0; b < 8; ++b)
        acc2 = rc::blendHiBit((acc << b) & 128 ? 255 : 0, acc2, c.ranzero2[b], c.ranone2[b], RcConstants::alpha);
    return acc2;
}

double idealNoise(const Params& params, const Tables& T, const RcConstants& c, int S, int Tc, int R) {
    const Format& f = params.format;
    const int v[3] = {S, Tc, R}, m = (1 << f.bf) - 1, cells = 1 << f.bi();
    int K[3];
    double u[3];
    for (int a = 0; a < 3; ++a) {
        K[a] = v[a] >> f.bf;
        u[a] = params.variant == Variant::Sgi ? double(v[a] & m) / m : double(v[a] & m) / (1 << f.bf);
        // (Rc: F << b_i / 255 = u 256/255 is the weight the passes use; Xor: u exactly)
        if (params.interp == Interp::Scurve) u[a] = u[a] * u[a] * (3 - 2 * u[a]);
    }
    double n = 0;
    for (int corner = 0; corner < 8; ++corner) {
        double w = 1;
        int L[3];
        for (int a = 0; a < 3; ++a) {
            const int bit = corner >> a & 1;
            w *= bit ? u[a] : 1 - u[a];
            L[a] = params.variant == Variant::Xor ? K[a] + bit : (K[a] + bit) % cells;
        }
        n += w * latticeValue(params, T, c, L[0], L[1], L[2]) / double(f.max());
    }
    return n;
}

Summary summarize(const std::vector<double>& v, double lo, double hi, int bins) {
    Summary s;
    if (v.empty()) return s;
    double sum = 0;
    s.min = s.max = v[0];
    for (double x : v) sum += x, s.min = std::min(s.min, x), s.max = std::max(s.max, x);
    s.mean = sum / v.size();
    double m2 = 0, m4 = 0;
    for (double x : v) {
        const double d = (x - s.mean) * (x - s.mean);
        m2 += d, m4 += d * d;
    }
    m2 /= v.size(), m4 /= v.size();
    s.stddev = std::sqrt(m2);
    s.excessKurtosis = m2 > 0 ? m4 / (m2 * m2) - 3.0 : 0.0;
    s.histogram.assign(bins, 0.0);
    for (double x : v) {
        const int b = std::clamp(int((x - lo) / (hi - lo) * bins), 0, bins - 1);
        s.histogram[b] += 1.0 / v.size();
    }
    return s;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    const size_t n = std::min(a.size(), b.size());
    if (n == 0) return 0;
    double ma = 0, mb = 0;
    for (size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
    ma /= n, mb /= n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0;
}

}  // namespace pst::multipass
