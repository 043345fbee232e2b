// Anisotropic noise (Goldberg, Zwicker, Durand 2008), sections 2-4. See subband.h.
#include "subband.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include <Eigen/Dense>
#include <fftw3.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace pst {

namespace {
constexpr double kPi = 3.141592653589793;

// Seeded white noise: splitmix64 uniforms, Box-Muller normals (portable, unlike <random>'s
// normal_distribution).
struct SplitMix {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return (double(next() >> 11) + 0.5) * 0x1.0p-53; }  // (0, 1)
};

double alpha2(int K) {
    // alpha_K^2 = 2^{2(K-1)} ((K-1)!)^2 / (K (2(K-1))!)  (eq. 1's alpha_K squared)
    const double n = K - 1;
    return std::exp(2 * n * std::log(2.0) + 2 * std::lgamma(n + 1) - std::log(double(K)) - std::lgamma(2 * n + 1));
}

// The standard deviation of Rayshade's noise (the other bases' scale), over the same R3
// low-discrepancy points as texture.cpp's noiseMoments.
double rayshadeSd() {
    static const double sd = [] {
        const double g = 1.2207440846057596, a1 = 1 / g, a2 = 1 / (g * g), a3 = 1 / (g * g * g);
        double sum = 0, sum2 = 0;
        const int n = 65536;
        for (int i = 1; i <= n; ++i) {
            const glm::dvec3 p(std::fmod(0.5 + a1 * i, 1.0), std::fmod(0.5 + a2 * i, 1.0), std::fmod(0.5 + a3 * i, 1.0));
            const double v = noise(64.0 * p, NoiseOptions{});
            sum += v;
            sum2 += v * v;
        }
        const double m = sum / n;
        return std::sqrt(std::max(0.0, sum2 / n - m * m));
    }();
    return sd;
}
}  // namespace

double subbandAngular(int K, int i, double theta) {
    const double c = std::cos(theta - kPi * i / K);
    return alpha2(K) * std::pow(c * c, K - 1);
}

double subbandRadial(int j, double r) {
    const double x = std::exp2(j) * r;
    if (!(x > kPi / 8 && x < kPi / 2)) return 0.0;
    const double c = std::cos(kPi / 2 * std::log2(4 * x / kPi));
    return c * c;
}

double subbandFilter(int K, int i, int j, const glm::dvec2& w) {
    const double r = glm::length(w);
    if (r == 0.0) return 0.0;
    return subbandAngular(K, i, std::atan2(w.y, w.x)) * subbandRadial(j, r);
}

glm::dvec2 subbandCentre(int K, int i, int j) {
    const double r = kPi / 4 * std::exp2(-j), a = kPi * i / K;
    return r * glm::dvec2(std::cos(a), std::sin(a));
}

namespace {
// subbandCentre's values for K = 4 and 8, [j K + i], computed once (the per-sample loops).
const glm::dvec2* centres(int K) {
    if (K != 4 && K != 8) throw std::invalid_argument("subband: orientations must be 4 or 8");
    static const auto table = [] {
        std::array<std::array<glm::dvec2, 8 * kSubbandScales>, 2> t{};
        for (int n = 0; n < 2; ++n) {
            const int k = n == 0 ? 4 : 8;
            for (int j = 0; j < kSubbandScales; ++j)
                for (int i = 0; i < k; ++i) t[n][j * k + i] = subbandCentre(k, i, j);
        }
        return t;
    }();
    return table[K == 4 ? 0 : 1].data();
}
}  // namespace

size_t subbandTileBytes(int K, int size) {
    const size_t px = size_t(size) * size, count = size_t(K) * kSubbandScales;
    return 3 * (count + kSubbandScales) * px * sizeof(float) + px * sizeof(double) + count * count * sizeof(double);
}

bool subbandValidSize(long long size) {
    return size >= kSubbandMinTile && size <= kSubbandMaxTile && (size & (size - 1)) == 0;
}

// ---- Section 2: spectral noise synthesis ---------------------------------------------------

namespace {
std::unique_ptr<SubbandTiles> buildTiles(int K, int N, uint64_t seed) {
    auto t = std::make_unique<SubbandTiles>();
    t->K = K;
    t->size = N;
    t->seed = seed;
    const size_t px = size_t(N) * N, half = size_t(N) * (N / 2 + 1);
    // Step 1: complex white noise F, the FFT of real white noise (Hermitian by construction).
    SplitMix rng{seed * 0x2545f4914f6cdd1dULL + 1};
    t->white.resize(px);
    for (size_t k = 0; k < px; k += 2) {
        const double u1 = rng.uniform(), u2 = rng.uniform(), r = std::sqrt(-2 * std::log(u1));
        t->white[k] = r * std::cos(2 * kPi * u2);
        t->white[k + 1] = r * std::sin(2 * kPi * u2);
    }
    double* real = fftw_alloc_real(px);
    fftw_complex* F = fftw_alloc_complex(half);
    fftw_complex* spec = fftw_alloc_complex(half);
    fftw_plan fwd = fftw_plan_dft_r2c_2d(N, N, real, F, FFTW_ESTIMATE);
    fftw_plan inv = fftw_plan_dft_c2r_2d(N, N, spec, real, FFTW_ESTIMATE);
    std::copy(t->white.begin(), t->white.end(), real);
    fftw_execute(fwd);

    const int S = kSubbandScales, count = K * S;
    t->value.resize(px * count);
    t->dx.resize(px * count);
    t->dy.resize(px * count);
    t->isoValue.assign(px * S, 0.f);
    t->isoDx.assign(px * S, 0.f);
    t->isoDy.assign(px * S, 0.f);
    const int W = N / 2 + 1;
    // Steps 2-3: N_ij = F D_ij, n_ij = IFFT(N_ij); derivatives from i w N_ij. FFTW's c2r is
    // unnormalized: divide by N^2.
    const double norm = 1.0 / double(px);
    for (int j = 0; j < S; ++j) {
        for (int i = 0; i < K; ++i) {
            const int k = j * K + i;
            for (int comp = 0; comp < 3; ++comp) {
                for (int ky = 0; ky < N; ++ky) {
                    const int fy = ky <= N / 2 ? ky : ky - N;
                    for (int kx = 0; kx < W; ++kx) {
                        const glm::dvec2 w(2 * kPi * kx / N, 2 * kPi * fy / N);
                        const double d = subbandFilter(K, i, j, w) * norm;
                        std::complex<double> c(F[size_t(ky) * W + kx][0], F[size_t(ky) * W + kx][1]);
                        c *= d;
                        // The derivative's Nyquist bins have no sign: drop them.
                        if (comp == 1) c *= kx == N / 2 ? 0.0 : 1.0, c *= std::complex<double>(0, w.x);
                        if (comp == 2) c *= ky == N / 2 ? 0.0 : 1.0, c *= std::complex<double>(0, w.y);
                        spec[size_t(ky) * W + kx][0] = c.real();
                        spec[size_t(ky) * W + kx][1] = c.imag();
                    }
                }
                fftw_execute(inv);
                std::vector<float>& dst = comp == 0 ? t->value : comp == 1 ? t->dx : t->dy;
                std::vector<float>& iso = comp == 0 ? t->isoValue : comp == 1 ? t->isoDx : t->isoDy;
                for (size_t p = 0; p < px; ++p) {
                    dst[size_t(k) * px + p] = float(real[p]);
                    iso[size_t(j) * px + p] += float(real[p]);
                }
            }
        }
    }
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(inv);
    fftw_free(real);
    fftw_free(F);
    fftw_free(spec);

    // The Gram matrix of the value tiles (their covariance over the tile: each has mean 0).
    t->gram.assign(size_t(count) * count, 0.0);
    for (int a = 0; a < count; ++a)
        for (int b = a; b < count; ++b) {
            const float* x = &t->value[size_t(a) * px];
            const float* y = &t->value[size_t(b) * px];
            double s = 0;
            for (size_t p = 0; p < px; ++p) s += double(x[p]) * y[p];
            t->gram[size_t(a) * count + b] = t->gram[size_t(b) * count + a] = s / double(px);
        }
    return t;
}

double bilinear(const float* tile, int N, const glm::dvec2& p) {
    const double fx = std::floor(p.x), fy = std::floor(p.y);
    const double tx = p.x - fx, ty = p.y - fy;
    const int m = N - 1;
    // Periodic: N is a power of two, so & m wraps negative indices too.
    const int x0 = int(int64_t(fx) & m), y0 = int(int64_t(fy) & m), x1 = (x0 + 1) & m, y1 = (y0 + 1) & m;
    const double a = tile[y0 * N + x0], b = tile[y0 * N + x1], c = tile[y1 * N + x0], d = tile[y1 * N + x1];
    return (a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + d * tx) * ty;
}
}  // namespace

double SubbandTiles::lookup(int k, const glm::dvec2& p, glm::dvec2* grad) const {
    const size_t px = size_t(size) * size;
    if (grad) *grad = glm::dvec2(bilinear(&dx[k * px], size, p), bilinear(&dy[k * px], size, p));
    return bilinear(&value[k * px], size, p);
}

double SubbandTiles::lookupIso(int j, const glm::dvec2& p, glm::dvec2* grad) const {
    const size_t px = size_t(size) * size;
    if (grad) *grad = glm::dvec2(bilinear(&isoDx[j * px], size, p), bilinear(&isoDy[j * px], size, p));
    return bilinear(&isoValue[j * px], size, p);
}

const SubbandTiles& subbandTiles(int K, int size, uint64_t seed) {
    if (K != 4 && K != 8) throw std::invalid_argument("subbandTiles: orientations must be 4 or 8");
    if (!subbandValidSize(size)) throw std::invalid_argument("subbandTiles: size must be a power of two in [256, 1024]");
    static std::mutex mu;  // also serialises FFTW's planner, which is not thread-safe
    static std::map<std::tuple<int, int, uint64_t>, std::unique_ptr<SubbandTiles>> cache;
    std::lock_guard<std::mutex> lock(mu);
    auto& slot = cache[{K, size, seed}];
    if (!slot) slot = buildTiles(K, size, seed);
    return *slot;
}

// ---- Sections 3 and 4: the weights ---------------------------------------------------------

double subbandTarget(const glm::dvec2& xi) { return subbandRadial(kSubbandCentreScale, glm::length(xi)); }

void subbandCompensation(int K, const glm::dmat2& T, double* gamma) {
    const glm::dvec2* c = centres(K);
    const glm::dmat2 Tt = glm::transpose(T);
    for (int k = 0; k < K * kSubbandScales; ++k) gamma[k] = subbandTarget(Tt * c[k]);
}

double subbandLowPass(const glm::dmat2& J, const glm::dvec2& w, double sigma) {
    // Eq. 4: exp(-sigma^2/2 w^T J J^T w).
    const glm::dvec2 v = glm::transpose(J) * w;
    return std::exp(-0.5 * sigma * sigma * glm::dot(v, v));
}

void subbandFilterHeuristic(int K, const glm::dmat2& J, double* lambda, double sigma) {
    const glm::dvec2* c = centres(K);
    for (int k = 0; k < K * kSubbandScales; ++k) lambda[k] = subbandLowPass(J, c[k], sigma);
}

namespace {
// A polar quadrature of the frequency plane over the bands' support (pi/128 .. pi/2): radii
// log-spaced, kLsPerOctave per octave, angles over [0, pi) (every function here is even), each
// point's area r^2 dlnr dtheta (doubled for the other half plane); the filters at each point.
struct LsQuadrature {
    std::vector<glm::dvec2> w;
    std::vector<double> area;
    std::vector<std::vector<std::pair<int, double>>> d;  // nonzero D_k at each point
    Eigen::LDLT<Eigen::MatrixXd> gram;                   // integral of D_k D_l
};
constexpr int kLsPerOctave = 8, kLsAngles = 48;

const LsQuadrature& lsQuadrature(int K) {
    static std::mutex mu;
    static std::map<int, std::unique_ptr<LsQuadrature>> cache;
    std::lock_guard<std::mutex> lock(mu);
    auto& slot = cache[K];
    if (slot) return *slot;
    slot = std::make_unique<LsQuadrature>();
    LsQuadrature& q = *slot;
    const int count = K * kSubbandScales;
    const double lo = std::log2(kPi / 8) - (kSubbandScales - 1), hi = std::log2(kPi / 2);
    const int nr = int(std::lround((hi - lo) * kLsPerOctave));
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(count, count);
    for (int a = 0; a < nr; ++a) {
        const double lr = lo + (a + 0.5) / kLsPerOctave, r = std::exp2(lr);
        for (int b = 0; b < kLsAngles; ++b) {
            const double th = kPi * (b + 0.5) / kLsAngles;
            const glm::dvec2 w = r * glm::dvec2(std::cos(th), std::sin(th));
            const double dA = 2 * r * r * std::log(2.0) / kLsPerOctave * (kPi / kLsAngles);
            std::vector<std::pair<int, double>> nz;
            for (int k = 0; k < count; ++k) {
                const double v = subbandFilter(K, k % K, k / K, w);
                if (v > 0) nz.push_back({k, v});
            }
            for (auto& x : nz)
                for (auto& y : nz) G(x.first, y.first) += dA * x.second * y.second;
            q.w.push_back(w);
            q.area.push_back(dA);
            q.d.push_back(std::move(nz));
        }
    }
    q.gram.compute(G);
    return q;
}
}  // namespace

void subbandFilterLeastSquares(int K, const glm::dmat2& J, double* lambda, double sigma) {
    // Eq. 5 in the least-squares sense: the normal equations G lambda = b, G_kl = int D_k D_l,
    // b_k = int H(J^T w) D_k.
    const LsQuadrature& q = lsQuadrature(K);
    const int count = K * kSubbandScales;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(count);
    for (size_t p = 0; p < q.w.size(); ++p) {
        const double h = q.area[p] * subbandLowPass(J, q.w[p], sigma);
        if (h < 1e-300) continue;
        for (auto& x : q.d[p]) b(x.first) += h * x.second;
    }
    const Eigen::VectorXd l = q.gram.solve(b);
    for (int k = 0; k < count; ++k) lambda[k] = l(k);
}

// ---- The basis ------------------------------------------------------------------------------

double subbandCentreScale(const SubbandTiles& t) {
    // subbandNoise's gamma^T C gamma with gamma = 1 on the centre scale (the same sum, in the
    // same order).
    const int K = t.K, count = t.count(), jc = kSubbandCentreScale;
    double var = 0;
    for (int a = jc * K; a < (jc + 1) * K; ++a)
        for (int b = jc * K; b < (jc + 1) * K; ++b) var += t.gram[size_t(a) * count + b];
    return var > 0 ? rayshadeSd() / std::sqrt(var) : 0.0;
}

namespace {
// (u, v) in noise units at p, and the 2 x 3 derivative DP (rows du/dp, dv/dp) along the assumed
// surface; T the distortion (isometric surface coordinates to (u, v)).
struct Param {
    glm::dvec2 uv;
    glm::dvec3 du, dv;
    glm::dmat2 T = glm::dmat2(1.0);
};

Param parameterize(const glm::dvec3& p, const NoiseOptions& opt) {
    Param r;
    switch (opt.param) {
    case SubbandParam::XY: r.uv = {p.x, p.y}, r.du = {1, 0, 0}, r.dv = {0, 1, 0}; return r;
    case SubbandParam::XZ: r.uv = {p.x, p.z}, r.du = {1, 0, 0}, r.dv = {0, 0, 1}; return r;
    case SubbandParam::YZ: r.uv = {p.y, p.z}, r.du = {0, 1, 0}, r.dv = {0, 0, 1}; return r;
    case SubbandParam::Sphere: break;
    }
    // Longitude about y, latitude; v = rad lat (arc length), u = rhoU lon with rhoU the radius
    // rounded so that a whole number of tile periods fits around the sphere (no seam).
    const double rad = std::max(glm::length(p), 1e-12);
    const double lon = std::atan2(p.z, p.x), lat = std::asin(std::clamp(p.y / rad, -1.0, 1.0));
    const double period = opt.tileSize / kSubbandUnitPx;
    const double rhoU = period * std::max(1.0, std::round(2 * kPi * rad / period)) / (2 * kPi);
    const double cl = std::max(std::cos(lat), 1e-3);
    const glm::dvec3 east(-std::sin(lon), 0, std::cos(lon));
    const glm::dvec3 north(-std::sin(lat) * std::cos(lon), std::cos(lat), -std::sin(lat) * std::sin(lon));
    r.uv = {rhoU * lon, rad * lat};
    // Along the sphere: du = rhoU / (rad cos lat) per unit of east arc length, dv = 1 per unit north.
    r.du = east * (rhoU / (rad * cl));
    r.dv = north;
    r.T = glm::dmat2(glm::dvec2(rhoU / (rad * cl), 0), glm::dvec2(0, 1));
    return r;
}
}  // namespace

double subbandNoise(const glm::dvec3& p, const NoiseOptions& opt, SubbandFilterKind kind, const glm::dvec3& dpdx,
                    const glm::dvec3& dpdy, glm::dvec3* grad, double* keptVar) {
    if (grad) *grad = glm::dvec3(0.0);
    if (keptVar) *keptVar = 1.0;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return 0.0;
    // The last tiles this thread used (the cache's lock is not taken per sample).
    thread_local const SubbandTiles* last = nullptr;
    if (!last || last->K != opt.orientations || last->size != opt.tileSize || last->seed != opt.seed)
        last = &subbandTiles(opt.orientations, opt.tileSize, opt.seed);
    const SubbandTiles& t = *last;
    const int K = t.K, count = t.count(), jc = kSubbandCentreScale;
    const Param pr = parameterize(p, opt);
    const glm::dvec2 q = kSubbandUnitPx * pr.uv;  // tile pixels
    const bool undistorted = pr.T == glm::dmat2(1.0);

    // Section 3.1: gamma (undistorted: 1 on the centre scale, 0 elsewhere), normalised so that the
    // octave's variance is Rayshade's: sd / sqrt(gamma^T C gamma). Only the nonzero gammas count.
    double gamma[8 * kSubbandScales], lambda[8 * kSubbandScales];
    int active[8 * kSubbandScales], na = 0;
    if (undistorted) {
        for (int k = 0; k < count; ++k) gamma[k] = k / K == jc ? 1.0 : 0.0;
    } else {
        subbandCompensation(K, pr.T, gamma);
    }
    for (int k = 0; k < count; ++k)
        if (gamma[k] != 0.0) active[na++] = k;
    auto quadratic = [&](const double* w) {
        double v = 0;
        for (int a = 0; a < na; ++a)
            for (int b = 0; b < na; ++b) v += w[active[a]] * w[active[b]] * t.gram[size_t(active[a]) * count + active[b]];
        return v;
    };
    const double var = quadratic(gamma);
    const double scale = var > 0 ? rayshadeSd() / std::sqrt(var) : 0.0;

    auto toP = [&](const glm::dvec2& g) { return kSubbandUnitPx * (g.x * pr.du + g.y * pr.dv); };
    if (kind == SubbandFilterKind::None && undistorted) {
        // The isotropic band-limited sum (all orientations of the centre scale): one lookup.
        glm::dvec2 g;
        const double v = t.lookupIso(jc, q, grad ? &g : nullptr);
        if (grad) *grad = scale * toP(g);
        return scale * v;
    }
    std::fill(lambda, lambda + count, 1.0);
    if (kind != SubbandFilterKind::None) {
        // J: tile pixels per screen pixel, columns d(u,v)/dx, d(u,v)/dy.
        const glm::dmat2 J(kSubbandUnitPx * glm::dvec2(glm::dot(pr.du, dpdx), glm::dot(pr.dv, dpdx)),
                           kSubbandUnitPx * glm::dvec2(glm::dot(pr.du, dpdy), glm::dot(pr.dv, dpdy)));
        glm::dmat2 Jf = J;
        if (kind == SubbandFilterKind::Isotropic) {
            // The isotropic Gaussian as wide as the footprint's major axis (J's largest singular value).
            const glm::dmat2 A = J * glm::transpose(J);
            const double tr = A[0][0] + A[1][1], det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
            Jf = glm::dmat2(std::sqrt(std::max(0.0, 0.5 * tr + std::sqrt(std::max(0.0, 0.25 * tr * tr - det)))));
        }
        if (opt.weights == SubbandWeights::LeastSquares) {
            subbandFilterLeastSquares(K, Jf, lambda, opt.sigma);
        } else {
            for (int a = 0; a < na; ++a) {
                const int k = active[a];
                lambda[k] = subbandLowPass(Jf, centres(K)[k], opt.sigma);
            }
        }
    }
    // Eq. 7: sum lambda_ij gamma_ij n_ij, skipping the weights too small to matter.
    double w[8 * kSubbandScales], wmax = 0;
    for (int a = 0; a < na; ++a) wmax = std::max(wmax, std::abs(w[active[a]] = lambda[active[a]] * gamma[active[a]]));
    double v = 0;
    glm::dvec2 g(0.0);
    for (int a = 0; a < na; ++a) {
        const int k = active[a];
        if (std::abs(w[k]) <= 1e-6 * wmax) continue;
        glm::dvec2 gk;
        v += w[k] * t.lookup(k, q, grad ? &gk : nullptr);
        if (grad) g += w[k] * gk;
    }
    if (keptVar && var > 0) *keptVar = quadratic(w) / var;
    if (grad) *grad = scale * toP(g);
    return scale * v;
}

}  // namespace pst
