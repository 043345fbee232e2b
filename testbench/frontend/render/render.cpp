#include "render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "interrupt.h"

namespace pst {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Rasterizes every object of one layer; layers above 0 are depth-tested against layer 0.
FragmentBuffer rasterizeLayer(const Scene& scene, int layer, const FragmentBuffer* occluder,
                              const SampleOffset& offset) {
    FragmentBuffer fb(scene.camera.width, scene.camera.height);
    for (size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].layer == layer)
            rasterize(scene.camera, scene.objects[i].mesh, static_cast<int>(i), fb, occluder, offset);
    return fb;
}

// "over" compositing of a straight-alpha colour onto the accumulated pixel.
inline void over(float* dst, const glm::dvec4& src) {
    const double a = std::clamp(src.a, 0.0, 1.0);
    for (int c = 0; c < 3; ++c) dst[c] = float(src[c] * a + dst[c] * (1.0 - a));
    dst[3] = float(a + dst[3] * (1.0 - a));
}

void fillBackground(Image& img, const glm::dvec4& bg) {
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 4; ++c) img.pixel(x, y)[c] = float(bg[c]);
}

// Stateless per-sample jitter: a 64-bit mix of (seed, pixel, sample index).
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
inline double unit(uint64_t h) { return double(h >> 11) * (1.0 / 9007199254740992.0); }

// The filtered colour of one fragment with the texture's filter kind and bandlimit replaced;
// f and gradS are the plain texture's (evalF). *w: the filter width used (entries / N).
glm::dvec4 shadeFiltered(const Texture& tex, const Fragment& fr, double f, glm::dvec3 gradS, FilterKind kind,
                         Bandlimit bandlimit, bool widthCap, double* w) {
    double fb = f, sd = 0;  // bandlimited octaves: only the filtered image
    Texture const* t = &tex;
    Texture copy;
    if (bandlimit != tex.bandlimit) {
        copy = tex;
        copy.bandlimit = bandlimit;
        t = &copy;
    }
    if (bandlimit != Bandlimit::Off) fb = evalFBandlimited(*t, fr.s, fr.dsdx, fr.dsdy, &gradS, &sd);
    *w = bandlimit != Bandlimit::Off ? bandlimitedWidth(*t, gradS, fr.dsdx, fr.dsdy, sd)
                                     : filterWidth(gradS, fr.dsdx, fr.dsdy, tex.norm);
    glm::dvec2 wxy = bandlimitedFootprint(*t, footprintWidths(gradS, fr.dsdx, fr.dsdy), sd);
    if (widthCap) capWidth(tex, w, &wxy);
    return filterColour(tex.clut, fb, *w, wxy, kind);
}

}  // namespace

bool parseVariant(const std::string& spec, FilterVariant* out, std::string* why) {
    FilterVariant v;
    v.name = spec;
    std::string body = spec;
    if (body.size() > 4 && body.compare(body.size() - 4, 4, "+cap") == 0) {
        v.widthCap = true;   // the filter-width cap (issue 44 part 2)
        body.resize(body.size() - 4);
    }
    const size_t plus = body.find('+');
    const std::string kind = body.substr(0, plus);
    if (!parseFilterKind(kind, &v.filter)) {
        *why = "'" + kind + "' is not a filter kind (none, mip, mip_linear, sat, box, trapezoid)";
        return false;
    }
    if (plus != std::string::npos && !parseBandlimit(body.substr(plus + 1), &v.bandlimit)) {
        *why = "'" + body.substr(plus + 1) + "' is not a bandlimit (off, footprint, isotropic, anisotropic)";
        return false;
    }
    *out = v;
    return true;
}

void parallelRows(int n, int threads, const std::function<void(int)>& body) {
    int t = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    t = std::min(t, std::max(1, n));
    std::atomic<int> next{0};
    // A stop request (SIGINT, SIGTERM: interrupt.h) ends every worker after its current row.
    auto worker = [&] {
        for (int y; !interrupted() && (y = next.fetch_add(1)) < n;) body(y);
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < t; ++i) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    throwIfInterrupted();
}

std::vector<Fragment> sceneFragments(const Scene& scene, int layer) {
    FragmentBuffer base = rasterizeLayer(scene, 0, nullptr, pixelCentre());
    FragmentBuffer fb = layer == 0 ? base : rasterizeLayer(scene, layer, &base, pixelCentre());
    std::vector<Fragment> out;
    for (const auto& f : fb.fragments())
        if (f.object >= 0) out.push_back(f);
    return out;
}

RenderResult render(const Scene& scene, const RenderOptions& opt) {
    const int W = scene.camera.width, H = scene.camera.height;
    RenderResult res;
    res.filtered = Image(W, H, 4);
    res.unfiltered = Image(W, H, 4);
    res.filterWidth = Image(W, H, 1);
    fillBackground(res.filtered, scene.background);
    fillBackground(res.unfiltered, scene.background);
    for (size_t v = 0; v < opt.variants.size(); ++v) {
        res.variants.emplace_back(W, H, 4);
        fillBackground(res.variants.back(), scene.background);
    }
    auto report = [&](const std::string& phase, double frac) {
        if (opt.progress) opt.progress(phase, frac);
    };

    // Step 1: rasterize each layer at pixel centres (layer 0 is the z-buffered opaque pass).
    auto t0 = Clock::now();
    std::vector<FragmentBuffer> layers;
    layers.push_back(rasterizeLayer(scene, 0, nullptr, pixelCentre()));
    for (int l = 1; l < scene.layers(); ++l)
        layers.push_back(rasterizeLayer(scene, l, &layers[0], pixelCentre()));
    res.stats.rasterSeconds = since(t0);

    // Step 2: shade: f and grad_s f (eq. 1, 10-12), w (section 3.2), filtered colour (eq. 9)
    // and the point sample (eq. 2), then composite the layers in order.
    t0 = Clock::now();
    std::atomic<long long> frags{0};
    std::atomic<int> rowsDone{0};
    parallelRows(H, opt.threads, [&](int y) {
        long long n = 0;
        for (int x = 0; x < W; ++x) {
            for (size_t l = 0; l < layers.size(); ++l) {
                const Fragment& fr = layers[l].at(x, y);
                if (fr.object < 0) continue;
                const Texture& tex = scene.textures[scene.objects[fr.object].texture];
                glm::dvec3 gradS;
                const double f = evalF(tex, fr.s, &gradS);
                double w = 0, wv = 0;
                over(res.filtered.pixel(x, y), shadeFiltered(tex, fr, f, gradS, tex.filter, tex.bandlimit, tex.widthCap, &w));
                for (size_t v = 0; v < opt.variants.size(); ++v)
                    over(res.variants[v].pixel(x, y),
                         shadeFiltered(tex, fr, f, gradS, opt.variants[v].filter, opt.variants[v].bandlimit,
                                       opt.variants[v].widthCap, &wv));
                over(res.unfiltered.pixel(x, y), tex.clut.sample(f));
                if (l == 0) res.filterWidth.pixel(x, y)[0] = float(w * tex.clut.size());
                ++n;
            }
        }
        frags += n;
        int done = ++rowsDone;
        if ((done & 31) == 0 || done == H) report("shade", double(done) / H);
    });
    res.stats.fragments = frags;
    res.stats.shadeSeconds = since(t0);

    // Step 3: ground truth: n x n stratified jittered point samples per pixel, unfiltered.
    if (opt.truthSamples > 0) {
        t0 = Clock::now();
        const int n = opt.truthSamples;
        res.truth = Image(W, H, 4);
        Image sample(W, H, 4);
        for (int k = 0; k < n * n; ++k) {
            const int si = k % n, sj = k / n;
            SampleOffset jitter = [&, si, sj, k](int x, int y) {
                uint64_t h = mix64(opt.seed * 0x9e3779b97f4a7c15ULL ^ mix64((uint64_t(y) << 32 | uint32_t(x)) + uint64_t(k) * 0x632be59bd9b4e019ULL));
                return glm::dvec2((si + unit(h)) / n, (sj + unit(mix64(h))) / n);
            };
            std::vector<FragmentBuffer> sl;
            sl.push_back(rasterizeLayer(scene, 0, nullptr, jitter));
            for (int l = 1; l < scene.layers(); ++l)
                sl.push_back(rasterizeLayer(scene, l, &sl[0], jitter));
            fillBackground(sample, scene.background);
            parallelRows(H, opt.threads, [&](int y) {
                for (int x = 0; x < W; ++x) {
                    for (const auto& fb : sl) {
                        const Fragment& fr = fb.at(x, y);
                        if (fr.object < 0) continue;
                        const Texture& tex = scene.textures[scene.objects[fr.object].texture];
                        over(sample.pixel(x, y), tex.clut.sample(evalF(tex, fr.s)));
                    }
                    float* acc = res.truth.pixel(x, y);
                    const float* s = sample.pixel(x, y);
                    for (int c = 0; c < 4; ++c) acc[c] += s[c] / float(n * n);
                }
            });
            report("truth", double(k + 1) / (n * n));
        }
        res.stats.truthSeconds = since(t0);
    }
    return res;
}

}  // namespace pst
