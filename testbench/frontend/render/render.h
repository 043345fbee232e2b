// Rendering a scene through the reference model: rasterize each layer into a z-buffered
// fragment frame, shade every fragment (f, grad f, filter width, filtered and point-sampled
// colour), composite the layers "over" each other, and optionally build the supersampled
// ground truth (n x n jittered, unfiltered samples per pixel) that judges the filter.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "scene.h"

namespace pst {

// A float RGBA (or single-channel) image, row 0 at the top.
struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<float> data;

    Image() = default;
    Image(int w, int h, int c) : width(w), height(h), channels(c), data(size_t(w) * h * c, 0.f) {}
    float* pixel(int x, int y) { return &data[(size_t(y) * width + x) * channels]; }
    const float* pixel(int x, int y) const { return &data[(size_t(y) * width + x) * channels]; }
};

// A filter option applied to every texture of a scene (the ground-truth comparison of filters):
// the filter kind, the bandlimited octaves and the filter-width cap. Spelled "KIND[+BANDLIMIT][+cap]"
// (parseVariant), e.g. "sat", "trapezoid", "sat+footprint", "trapezoid+isotropic", "sat+cap",
// "sat+isotropic+cap".
struct FilterVariant {
    std::string name;
    FilterKind filter = FilterKind::Sat;
    Bandlimit bandlimit = Bandlimit::Off;
    bool widthCap = false;   // w = min(w, widthCapOf(texture)) (issue 44 part 2)
};
// false (and *why set) for a malformed spelling.
bool parseVariant(const std::string& spec, FilterVariant* out, std::string* why);

struct RenderOptions {
    int truthSamples = 0;   // n: n x n jittered unfiltered samples per pixel; 0 = no ground truth
    uint64_t seed = 1;      // jitter seed of the ground truth
    int threads = 0;        // 0 = all cores
    std::vector<FilterVariant> variants;  // extra filtered images, one per variant
    // Progress callback (phase name, fraction done); empty = silent.
    std::function<void(const std::string&, double)> progress;
};

struct RenderStats {
    long long fragments = 0;      // shaded fragments, all layers
    double rasterSeconds = 0;
    double shadeSeconds = 0;
    double truthSeconds = 0;
};

struct RenderResult {
    Image filtered;     // RGBA, each texture's own filter
    Image unfiltered;   // RGBA, point-sampled colour map at the pixel centre
    Image filterWidth;  // 1 channel: w * N (colour-table entries) of the front layer-0 fragment
    Image truth;        // RGBA, empty unless truthSamples > 0
    std::vector<Image> variants;  // RGBA, one per RenderOptions::variants
    RenderStats stats;
};

RenderResult render(const Scene& scene, const RenderOptions& options = {});

// The fragments of layer `layer` at pixel centres, in raster order (for fragment files and
// for streaming to the hardware models).
std::vector<Fragment> sceneFragments(const Scene& scene, int layer);

// Runs body(y) for y in [0, n) on `threads` threads (0 = all cores).
void parallelRows(int n, int threads, const std::function<void(int)>& body);

}  // namespace pst
