// Benchmarks of the noise bases of the reference model (part of build/testbench/pst_bench):
// one evaluation n(p) with its gradient at random points, per basis.
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "noise.h"

namespace pst {
namespace {

void BM_Noise(benchmark::State& st, NoiseOptions opt) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-100.0, 100.0);
    std::vector<glm::dvec3> pts(4096);
    for (auto& p : pts) p = glm::dvec3(u(rng), u(rng), u(rng));
    size_t i = 0;
    for (auto _ : st) {
        glm::dvec3 g;
        benchmark::DoNotOptimize(noise(pts[i++ & 4095], opt, &g));
        benchmark::DoNotOptimize(g);
    }
}

NoiseOptions basis(NoiseBasis b, std::array<double, 4> coef = {1, 0, 0, 0},
                   WorleyMetric m = WorleyMetric::Euclid) {
    NoiseOptions o;
    o.basis = b;
    o.coef = coef;
    o.metric = m;
    return o;
}

BENCHMARK_CAPTURE(BM_Noise, rayshade, basis(NoiseBasis::Rayshade));
BENCHMARK_CAPTURE(BM_Noise, perlin2002, basis(NoiseBasis::Perlin2002));
BENCHMARK_CAPTURE(BM_Noise, worley_F1, basis(NoiseBasis::Worley));
BENCHMARK_CAPTURE(BM_Noise, worley_F2_minus_F1, basis(NoiseBasis::Worley, {-1, 1, 0, 0}));
BENCHMARK_CAPTURE(BM_Noise, worley_F1_to_F4, basis(NoiseBasis::Worley, {1, 1, 1, 1}));
BENCHMARK_CAPTURE(BM_Noise, worley_F1_manhattan, basis(NoiseBasis::Worley, {1, 0, 0, 0}, WorleyMetric::Manhattan));

}  // namespace
}  // namespace pst
