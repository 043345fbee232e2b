// Quality of the multipass noise (Hart 2001; docs/MULTIPASS.md "Quality"): the noise the
// passes should give with exact arithmetic, and statistics of noise images and lattices.
#pragma once

#include <cstdint>
#include <vector>

#include "program.h"
#include "tables.h"

namespace pst::multipass {

// The lattice value (a byte) of the integer point (i, j, k), 0 <= i, j, k < 2^b_i, as the
// variant computes it: SGI nran[sran[i] + tran[j] + rran[k]] (section 4.3); register
// combiners the two bit-serial randomizations of section 5.3 with the combiner rounding;
// exclusive or the byte of 0.5 R[m] + 1/2, m Rayshade's Perm256 hash of (i, j, k) + 1e6
// (0 <= i, j, k <= 2^b_i: this variant's lattice does not wrap).
int latticeValue(const Params& params, const Tables& tables, const RcConstants& rc, int i, int j, int k);

// The register-combiner lattice before section 5.3's second step: tex_corrnan, the twelve
// (3 b_i) blends by the bits of i, j, k (Figure 11 (a)).
int rcFirstStage(const Params& params, const RcConstants& rc, int i, int j, int k);

// Figure 3 in double precision on the variant's lattice values: the weighted sum of the
// eight corners' lattice values / 255, weights u, 1 - u (SCURVE(u) for Interp::Scurve), u the
// variant's weight in exact arithmetic: SGI F / (2^b_f - 1) (section 4.2's fracshift),
// register combiners F / 2^b_f (scaled by 256/255, as F << b_i). S, T, R input bytes.
double idealNoise(const Params& params, const Tables& tables, const RcConstants& rc, int S, int T, int R);

// Moments and shape of a sample.
struct Summary {
    double mean = 0, stddev = 0, excessKurtosis = 0;  // uniform -1.2, Gaussian 0
    double min = 0, max = 0;
    std::vector<double> histogram;  // fraction of values in each of `bins` equal bins of [lo, hi]
};
Summary summarize(const std::vector<double>& v, double lo, double hi, int bins);

// Pearson correlation of two equal-length samples.
double correlation(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace pst::multipass
