#include "hwrender.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

#include "driver.h"
#include "imageio.h"
#include "interrupt.h"
#include "scoreboard.h"

namespace pst {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

inline void over(float* dst, const glm::dvec4& src) {
    const double a = std::clamp(src.a, 0.0, 1.0);
    for (int c = 0; c < 3; ++c) dst[c] = float(src[c] * a + dst[c] * (1.0 - a));
    dst[3] = float(a + dst[3] * (1.0 - a));
}

}  // namespace

ErrorStats compareToReference(const Image& hw, const Image& ref, int colourBits) {
    ErrorStats e;
    const double scale = double((1 << colourBits) - 1);
    size_t ok = 0, n = size_t(hw.width) * hw.height;
    for (size_t i = 0; i < n; ++i) {
        bool within = true;
        for (int c = 0; c < 3; ++c) {
            const double d = std::abs(std::round(hw.data[i * 4 + c] * scale) - std::round(ref.data[i * 4 + c] * scale));
            e.maxLsb = std::max(e.maxLsb, d);
            within = within && d <= 1.0;
        }
        ok += within;
    }
    const ImageDiff d = compareRgb(hw, ref);
    e.rms = d.rmsError;
    e.psnr = d.psnr;
    e.within1Lsb = n ? 100.0 * double(ok) / double(n) : 100.0;
    return e;
}

std::vector<PixelFx> runBatch(GoldenPipeline& golden, RtlModel* rtl, Scoreboard& board,
                              const std::vector<FragmentFx>& in, int activeOctaves, bool probes,
                              double& goldenSeconds, double& rtlSeconds, uint64_t* firstMismatchCycle) {
    auto tg = Clock::now();
    std::vector<PixelFx> expected(in.size());
    for (size_t i = 0; i < in.size(); ++i) {
        UnitTrace trace;
        expected[i] = golden.eval(in[i], rtl ? &trace : nullptr);
        if (rtl) board.expect(in[i], expected[i], trace);
    }
    goldenSeconds += since(tg);
    if (!rtl) return expected;
    auto tr = Clock::now();
    std::map<uint32_t, ProbeFx> sampled;
    std::vector<PixelFx> got = rtl->run(in, activeOctaves, probes ? &sampled : nullptr);
    rtlSeconds += since(tr);
    const std::vector<uint64_t>& outCycles = rtl->outCycles();
    for (size_t i = 0; i < got.size(); ++i) {
        const PixelFx& px = got[i];
        auto it = sampled.find(px.tag);
        const size_t before = board.mismatches() + board.unexpected();
        board.observe(px, it == sampled.end() ? nullptr : &it->second);
        if (firstMismatchCycle && *firstMismatchCycle == UINT64_MAX && board.mismatches() + board.unexpected() > before)
            *firstMismatchCycle = i < outCycles.size() ? outCycles[i] : rtl->cycles();
    }
    return got;
}

HwRenderResult renderHardware(const Scene& scene, const Profile& p, RtlModel* rtl, const HwRenderOptions& opt) {
    const int W = scene.camera.width, H = scene.camera.height;
    HwRenderResult res;
    auto report = [&](const std::string& s, double f) {
        if (opt.progress) opt.progress(s, f);
    };

    // The double reference, for the error figures.
    auto t0 = Clock::now();
    res.reference = render(scene).filtered;
    res.referenceSeconds = since(t0);
    Image truth;
    if (opt.truthSamples > 0) {
        RenderOptions ro;
        ro.truthSamples = opt.truthSamples;
        truth = render(scene, ro).truth;
    }

    res.hardware = Image(W, H, 4);
    for (size_t i = 0; i < size_t(W) * H; ++i)
        for (int c = 0; c < 4; ++c) res.hardware.data[i * 4 + c] = float(scene.background[c]);

    GoldenPipeline golden(p);
    golden.injectFault(opt.fault);
    Scoreboard board(p, opt.maxReports);
    std::set<std::string> notes;
    const uint64_t cycles0 = rtl ? rtl->busyCycles() : 0;

    for (int layer = 0; layer < scene.layers(); ++layer) {
        const std::vector<Fragment> frags = sceneFragments(scene, layer);
        // Objects in the order their first fragment appears: one texture program each.
        std::vector<int> order;
        std::map<int, std::vector<const Fragment*>> byObject;
        for (const Fragment& f : frags) {
            if (!byObject.count(f.object)) order.push_back(f.object);
            byObject[f.object].push_back(&f);
        }
        std::vector<glm::dvec4> colour(size_t(W) * H, glm::dvec4(0.0));
        std::vector<char> covered(size_t(W) * H, 0);
        for (int obj : order) {
            const Texture& tex = scene.textures[scene.objects[obj].texture];
            const TextureProgram prog = programTexture(p, tex);
            if (!prog.notes.empty()) notes.insert("texture '" + tex.name + "': " + prog.notes);
            for (const auto& [a, d] : prog.writes) golden.write(a, d);
            if (rtl) rtl->write(prog.writes);

            std::vector<FragmentFx> in;
            in.reserve(byObject[obj].size());
            for (const Fragment* f : byObject[obj])
                in.push_back(quantizeFragment(p, uint32_t(f->y * W + f->x), f->s, f->dsdx, f->dsdy));

            const std::vector<PixelFx> shown = runBatch(golden, rtl, board, in, prog.activeOctaves, opt.probes,
                                                        res.goldenSeconds, res.rtlSeconds, &res.firstMismatchCycle);
            for (const PixelFx& px : shown) {
                if (px.tag >= uint32_t(W) * H) continue;
                colour[px.tag] = unpackRgba(p, px.rgba);
                covered[px.tag] = 1;
            }
            res.fragments += (long long)in.size();
            throwIfInterrupted();   // SIGINT, SIGTERM: between the objects' batches
            report("layer " + std::to_string(layer), 1.0);
        }
        for (size_t i = 0; i < size_t(W) * H; ++i)
            if (covered[i]) over(&res.hardware.data[i * 4], colour[i]);
    }
    if (rtl) {
        const size_t lost0 = board.lost();
        board.finish();
        if (res.firstMismatchCycle == UINT64_MAX && board.lost() > lost0) res.firstMismatchCycle = rtl->cycles();
        res.passed = board.passed();
        res.pixels = board.checked();
        res.mismatches = board.mismatches();
        res.scoreboard = board.summary();
        res.byUnit = board.byUnit();
        res.cycles = rtl->busyCycles() - cycles0;
        res.cyclesPerPixel = res.fragments ? double(res.cycles) / double(res.fragments) : 0.0;
    } else {
        res.pixels = size_t(res.fragments);
    }
    res.notes.assign(notes.begin(), notes.end());

    res.vsReference = compareToReference(res.hardware, res.reference, p.colourBits);
    if (opt.truthSamples > 0) {
        res.vsTruth = compareToReference(res.hardware, truth, p.colourBits);
        res.referenceVsTruth = compareToReference(res.reference, truth, p.colourBits);
    }
    res.difference = Image(W, H, 4);
    for (size_t i = 0; i < size_t(W) * H; ++i) {
        for (int c = 0; c < 3; ++c)
            res.difference.data[i * 4 + c] =
                std::min(1.0f, 8.0f * std::abs(res.hardware.data[i * 4 + c] - res.reference.data[i * 4 + c]));
        res.difference.data[i * 4 + 3] = 1.0f;
    }
    return res;
}

}  // namespace pst
