// Benchmarks of the testbench (timings are measured here, never asserted in tests):
// rasterizing 512x512 frames and shading a scene through the reference model.
#include <cstdlib>
#include <string>

#include <benchmark/benchmark.h>

#include "rasterizer.h"
#include "render.h"
#include "scene.h"
#include "source_dir.h"

namespace pst {
namespace {

Camera camera(glm::dvec3 eye, glm::dvec3 target) {
    Camera c;
    c.eye = eye;
    c.target = target;
    return c;
}

void BM_RasterTeapot512(benchmark::State& st) {
    const Camera cam = camera({0.0, 4.0, 8.0}, {0.2, 1.4, 0.0});
    const Mesh teapot = makeTeapot(6);
    for (auto _ : st) {
        FragmentBuffer fb(cam.width, cam.height);
        rasterize(cam, teapot, 0, fb);
        benchmark::DoNotOptimize(fb.fragments().data());
    }
}
BENCHMARK(BM_RasterTeapot512)->Unit(benchmark::kMillisecond);

void BM_RasterHorizonPlane512(benchmark::State& st) {
    const Camera cam = camera({0.0, 1.0, 0.0}, {0.0, 0.8, -10.0});
    const Mesh ground = makePlane(1000.0, 1);
    for (auto _ : st) {
        FragmentBuffer fb(cam.width, cam.height);
        rasterize(cam, ground, 0, fb);
        benchmark::DoNotOptimize(fb.fragments().data());
    }
}
BENCHMARK(BM_RasterHorizonPlane512)->Unit(benchmark::kMillisecond);

// Reference-model rendering of a paper scene at 256x256 (pixels per second reported).
void BM_RenderScene256(benchmark::State& st, const char* name) {
    const Scene scene = loadScene(sourceDir() + "/scenes/" + name + ".toml", 256, 256);
    RenderOptions opt;
    opt.threads = 1;
    long long frags = 0;
    for (auto _ : st) frags += render(scene, opt).stats.fragments;
    st.counters["fragments/s"] = benchmark::Counter(double(frags), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_RenderScene256, wood_teapot, "wood_teapot")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderScene256, planet, "planet")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderScene256, bases, "bases")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pst

BENCHMARK_MAIN();
