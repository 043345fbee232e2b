// Anisotropic noise (Goldberg, Zwicker, Durand 2008): oriented subband tiles made in the
// frequency domain, summed with weights that compensate a 2-D parameterization's distortion
// (section 3) and approximate the pixel's Gaussian low-pass filter (section 4).
//
//   D_ij(w) = G_i(theta) B(2^j r)                                  (eq. 1)
//   n_ij    = IFFT(F D_ij), F the FFT of seeded white noise        (section 2)
//   gamma_ij = E(T^T w_ij)                       distortion compensation (section 3.1, heuristic)
//   lambda_ij = exp(-sigma^2/2 |J^T w_ij|^2)     the filter's weights (eq. 4, heuristic), or the
//               least-squares fit of sum lambda_ij D_ij to that Gaussian (eq. 5)
//   value   = sum_ij lambda_ij gamma_ij n_ij(M(x0, y0))             (eq. 7)
//
// Units: frequencies w in radians per tile pixel; a noise unit (one lattice cell of the other
// bases) is kSubbandUnitPx tile pixels, and the octave's band (scale kSubbandCentreScale) is
// centred on half a cycle per unit, as the lattice noises are roughly.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "noise.h"

namespace pst {

constexpr int kSubbandScales = 5;        // j = 0..4: centre frequency pi/4 2^-j
constexpr int kSubbandCentreScale = 2;   // one octave's band: pi/16 rad per pixel
constexpr double kSubbandUnitPx = 16.0;  // tile pixels per noise unit
constexpr int kSubbandMinTile = 256, kSubbandMaxTile = 1024;  // the coarsest band needs 256

// G_i(theta) of eq. 1: alpha_K^2 cos^{2(K-1)}(theta - pi i / K), alpha_K^2 = 2^{2(K-1)}
// ((K-1)!)^2 / (K (2(K-1))!), so that sum_i G_i = 1 (an even power: the filter is pi-periodic,
// the tiles are real).
double subbandAngular(int K, int i, double theta);
// The radial band of scale j at radius r (radians per pixel): cos^2(pi/2 log2(2^j 4 r / pi)) for
// pi/8 < 2^j r < pi/2, else 0. Eq. 1's H as printed is the roll-off's upper half (a low-pass);
// the band is L^2(2^j r) - L^2(2^{j+1} r) of that low-pass, so that the scales sum to one.
double subbandRadial(int j, double r);
// D_ij(w) (eq. 1).
double subbandFilter(int K, int i, int j, const glm::dvec2& w);
// The subband's centre w_ij: radius pi/4 2^-j, angle pi i / K.
glm::dvec2 subbandCentre(int K, int i, int j);

// The tiles of one (seed, K, size): n_ij, its derivatives along x and y (per tile pixel, by
// multiplying the spectrum by i w), the isotropic band-limited sums over the orientations of each
// scale, and their Gram matrix (mean of n_k n_l over the tile, k = j K + i).
struct SubbandTiles {
    int K = 0, size = 0;
    uint64_t seed = 0;
    std::vector<float> value, dx, dy;           // [k][y][x], k = j K + i
    std::vector<float> isoValue, isoDx, isoDy;  // [j][y][x]
    std::vector<double> gram;                   // [k][l]
    int count() const { return K * kSubbandScales; }
    // The white noise the tiles were filtered from (unit variance per pixel), for tests.
    std::vector<double> white;

    // Bilinear, periodic lookup of tile k (or scale j's isotropic sum) at p (tile pixels;
    // pixel (x, y) at integer p): the value, and the bilinear lookup of the derivative tiles.
    double lookup(int k, const glm::dvec2& p, glm::dvec2* grad) const;
    double lookupIso(int j, const glm::dvec2& p, glm::dvec2* grad) const;
};

// The factor subbandNoise scales the undistorted, unfiltered basis by (the isotropic sum of the
// centre scale, kSubbandCentreScale, to Rayshade noise's standard deviation): sd_R / sqrt(var),
// var the sum of the centre scale's Gram entries.
double subbandCentreScale(const SubbandTiles& t);

// Built once per (seed, K, size) and cached (thread-safe). K is 4 or 8; size a power of two in
// [kSubbandMinTile, kSubbandMaxTile] (std::invalid_argument otherwise).
const SubbandTiles& subbandTiles(int K, int size, uint64_t seed);
bool subbandValidSize(long long size);
// The memory one (seed, K, size) set takes once built (float tiles, the white noise, the Gram
// matrix), and the bound on a scene's distinct sets (checked by the scene parser).
size_t subbandTileBytes(int K, int size);
constexpr size_t kSubbandMaxSceneBytes = size_t(1) << 30;

// The isotropic target of one octave in the undistorted parameterization: E(xi) = B(2^jc |xi|).
double subbandTarget(const glm::dvec2& xi);
// Heuristic distortion compensation (section 3.1): gamma_ij = E(T^T w_ij), T the 2 x 2 map from
// isometric surface coordinates to texture coordinates (columns: T[0] = d(u,v)/ds).
void subbandCompensation(int K, const glm::dmat2& T, double* gamma);
// The Gaussian low-pass in texture space (eq. 4): exp(-sigma^2/2 |J^T w|^2), J the Jacobian of
// texture (tile pixels) over screen pixels, columns d(u,v)/dx and d(u,v)/dy.
double subbandLowPass(const glm::dmat2& J, const glm::dvec2& w, double sigma = 1.0);
// Eq. 5 weights: heuristic lambda_ij = the low-pass at w_ij; least squares: the lambda that
// minimises the integral of (low-pass - sum lambda D)^2 over the plane (a polar quadrature).
void subbandFilterHeuristic(int K, const glm::dmat2& J, double* lambda, double sigma = 1.0);
void subbandFilterLeastSquares(int K, const glm::dmat2& J, double* lambda, double sigma = 1.0);

// How a texture filters the subband basis.
enum class SubbandFilterKind {
    None,         // point sample: lambda = 1
    Isotropic,    // lambda from the isotropic Gaussian of the footprint's major axis
    Anisotropic,  // lambda from the footprint's Jacobian (eq. 4-5)
};

// The subband basis at the octave's point p = M s + o (3-D): opt.param maps p to (u, v) (noise
// units; "xy", "xz", "yz": two of its coordinates, the surface assumed in that plane;
// "sphere": longitude and latitude about the origin times the radius, the longitude's scale
// rounded so that the tile wraps around the sphere, the surface assumed a sphere about the
// origin; distortion compensated). dpdx, dpdy: the footprint's Jacobian columns in p (M dsdx,
// M dsdy), used unless kind is None. Returns the noise value (standard deviation that of
// Rayshade's noise, mean 0); grad: d/dp; keptVar: the share of the unfiltered variance kept.
double subbandNoise(const glm::dvec3& p, const NoiseOptions& opt, SubbandFilterKind kind, const glm::dvec3& dpdx,
                    const glm::dvec3& dpdy, glm::dvec3* grad = nullptr, double* keptVar = nullptr);

}  // namespace pst
