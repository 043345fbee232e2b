// pst regress SCENES: every scene x profile (x seed) through the RTL, checked against the golden
// model; a failing run's FST window with --waves.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "imageio.h"
#include "junit.h"
#include "provenance.h"
#include "regress.h"

namespace pst::cli {
namespace {

// The command that runs one scene x profile of a regression again, with the same inputs, gaps and stalls.
std::string regressReplay(const std::string& scene, int size, const std::string& profile, const SimOptions& so,
                          const std::string& fault) {
    std::ostringstream os;
    os << "pst regress " << scene << " --size " << size << " --profile " << profile;
    if (so.seed != SimOptions{}.seed) os << " --sim-seed " << so.seed;
    if (so.inputGapRate > 0) os << " --gap-rate " << so.inputGapRate;
    if (so.outputStallRate > 0) os << " --stall-rate " << so.outputStallRate;
    if (so.timeoutCycles) os << " --timeout " << so.timeoutCycles;
    if (so.busyWriteAfter) os << " --inject-assert " << so.busyWriteAfter - 1;
    if (!fault.empty()) os << " --inject-fault " << fault;
    return os.str();
}

// The scene as profile p runs it: a profile with the fade unit runs every scene with the
// hardware's bandlimited octaves on (its textures' bandlimit = "isotropic"; the reference
// renders the same). A subband unit with its filter (noise.subband_orientations) has the fade
// unit's table for its anisotropic weights: its subband textures run with "anisotropic" (it
// refuses "isotropic", which made a subband scene with bandlimit "off" an error, not a run).
Scene asRun(const Scene& scene, const Profile& p) {
    Scene s = scene;
    const bool sbFilter = p.noise.basis == NoiseBasis::Subband && p.noiseSubbandOrientations != 0;
    if (p.bandlimit())
        for (Texture& t : s.textures)
            if (t.bandlimit == Bandlimit::Off)
                t.bandlimit = sbFilter && t.noise.basis == NoiseBasis::Subband ? Bandlimit::Anisotropic
                                                                                : Bandlimit::Isotropic;
    return s;
}

struct Waves {
    std::string file;
    uint64_t cycle = 0, start = 0, end = 0;
};

// --waves: the failed run again (the same model, seed, gaps and stalls: the same cycles), traced
// from `before` cycles before the first mismatch (or assertion) at `cycle` to `after` after it.
Waves traceFailure(const RegressArgs& a, const Scene& scene, const Profile& p, const std::string& stem, SimOptions so,
                   const HwRenderOptions& ho, uint64_t cycle) {
    Waves w;
    w.cycle = cycle;
    w.start = cycle > a.wavesBefore ? cycle - a.wavesBefore : 0;
    w.end = cycle + a.wavesAfter;
    std::string name = stem + "." + p.name;
    if (a.seeds.size() > 1) name += ".seed" + std::to_string(so.seed);
    w.file = (fs::path(a.wavesShown.empty() ? a.waves : a.wavesShown) / (name + ".fst")).string();
    so.traceFile = (fs::path(a.waves) / (name + ".fst")).string();
    so.traceStart = w.start;
    so.traceEnd = w.end;
    auto rtl = makeRtlModel(p.name, so);
    try {
        renderHardware(scene, p, rtl.get(), ho);
    } catch (const RtlAssertionError&) {
        // the assertion fires again: its cycle is in the window
    }
    rtl.reset();   // closes the FST
    return w;
}

std::string wavesLine(const RegressArgs& a, const Waves* w) {
    if (w)
        return "waves: " + w->file + " (cycles " + std::to_string(w->start) + ".." + std::to_string(w->end) +
               ", first failure at cycle " + std::to_string(w->cycle) + "; open with gtkwave)";
    return "waves: add --waves DIR to the replay (an FST of the " + std::to_string(a.wavesBefore) +
           " cycles before the first failure)";
}

}  // namespace

int runRegressScenes(const RegressArgs& a, const HwArgs& hw) {
    nlohmann::json all = nlohmann::json::array();
    std::vector<JunitCase> cases;
    int failures = 0, skipped = 0;
    // Every scene and profile is loaded and checked before the first run writes anything.
    std::vector<Scene> loaded;
    for (const std::string& path : a.scenes) loaded.push_back(loadScene(path, a.size, a.size));
    std::vector<Profile> profiles;
    for (const std::string& name : hw.profiles) profiles.push_back(profileByName(name, true, false));
    const Unit fault = a.injectFault.empty() ? Unit::Count : unitByName(a.injectFault);
    // --inject-assert I fires once fragment I of a run is in: a run of at most I fragments could
    // not fire it and would pass, so every scene must have more (refused before any run).
    if (hw.sim.busyWriteAfter)
        for (size_t si = 0; si < loaded.size(); ++si) {
            size_t n = 0;
            for (int layer = 0; layer < loaded[si].layers(); ++layer) n += sceneFragments(loaded[si], layer).size();
            if (hw.sim.busyWriteAfter > n)
                throw InputError("--inject-assert: fragment " + std::to_string(hw.sim.busyWriteAfter - 1) +
                                 " is past the run of " + a.scenes[si] + " at --size " + std::to_string(a.size) +
                                 " (" + std::to_string(n) + " fragments); the self-test could not fire");
        }
    if (!a.waves.empty()) fs::create_directories(a.waves);
    const bool reseeded = a.seeds.size() > 1;
    std::printf("%-14s %-8s %9s %10s %8s %9s %10s %12s\n", "scene", "profile", "pixels", "mismatch", "PSNR",
                "<=1LSB%", "cyc/pixel", "rtl px/s");
    EtaProgress progress("regress", a.scenes.size() * profiles.size() * a.seeds.size(), a.quiet);
    for (uint64_t seed : a.seeds) {
        SimOptions sim = hw.sim;
        sim.seed = seed;
        if (reseeded) {
            std::printf("seed %llu\n", (unsigned long long)seed);
            std::fflush(stdout);
        }
        for (size_t si = 0; si < a.scenes.size(); ++si) {
            const std::string& path = a.scenes[si];
            const Scene& scene = loaded[si];
            const std::string stem = fs::path(path).stem().string();
            const std::string caseName = reseeded ? stem + " seed " + std::to_string(seed) : stem;
            for (const Profile& p : profiles) {
                throwIfInterrupted();   // SIGINT, SIGTERM: between runs (and inside them)
                // A scene the profile cannot run (a reference-only noise basis) is skipped, visibly,
                // and kept out of the JSON: it neither passes nor fails.
                if (std::string why = unsupportedTexture(scene, p); !why.empty()) {
                    std::printf("%-14s %-8s SKIPPED: %s\n", stem.c_str(), p.name.c_str(), why.c_str());
                    std::fflush(stdout);
                    ++skipped;
                    cases.push_back({"regress." + p.name, caseName, 0, false, why, "", true});
                    progress.step(stem + "/" + p.name);
                    continue;
                }
                auto rtl = makeRtlModel(p.name, sim);
                HwRenderOptions ho;
                ho.fault = fault;
                const Scene run = asRun(scene, p);
                const std::string replay = regressReplay(path, a.size, p.name, sim, a.injectFault);
                HwRenderResult r;
                try {
                    r = renderHardware(run, p, rtl.get(), ho);
                } catch (const RtlAssertionError& e) {
                    // A failed run like a mismatch: recorded, the next run goes on.
                    rtl.reset();
                    std::optional<Waves> w;
                    if (!a.waves.empty()) w = traceFailure(a, run, p, stem, sim, ho, e.cycle);
                    const std::string wl = wavesLine(a, w ? &*w : nullptr);
                    std::printf("%-14s %-8s ASSERTION at cycle %llu\n", stem.c_str(), p.name.c_str(),
                                (unsigned long long)e.cycle);
                    std::cout << e.what() << "\nreplay alone: " << replay << "\n" << wl << "\n";
                    std::fflush(stdout);
                    ++failures;
                    cases.push_back({"regress." + p.name, caseName, 0, true,
                                     "RTL assertion at cycle " + std::to_string(e.cycle),
                                     std::string(e.what()) + "\nreplay alone: " + replay + "\n" + wl + "\n"});
                    HwRenderResult none;   // the same keys as a finished run's, zero
                    none.passed = false;
                    nlohmann::json j = hwJson(path, p, "rtl", none, scene.camera.width, scene.camera.height);
                    j["assertion"] = {{"cycle", e.cycle}, {"pixels_out", e.pixelsOut}};
                    j["replay"] = replay;
                    if (reseeded) j["sim_seed"] = seed;
                    if (w) j["waves"] = {{"file", w->file}, {"cycle", w->cycle}, {"start", w->start}, {"end", w->end}};
                    all.push_back(j);
                    progress.step(stem + "/" + p.name);
                    continue;
                }
                rtl.reset();
                std::printf("%-14s %-8s %9lld %10zu %8.2f %9.2f %10.3f %12.0f\n", stem.c_str(), p.name.c_str(),
                            r.fragments, r.mismatches, r.vsReference.psnr, r.vsReference.within1Lsb, r.cyclesPerPixel,
                            r.rtlSeconds > 0 ? double(r.fragments) / r.rtlSeconds : 0.0);
                std::fflush(stdout);
                std::optional<Waves> w;
                std::string wl;
                if (!r.passed) {
                    ++failures;
                    std::cout << r.scoreboard;
                    if (!a.waves.empty() && r.firstMismatchCycle != UINT64_MAX)
                        w = traceFailure(a, run, p, stem, sim, ho, r.firstMismatchCycle);
                    wl = wavesLine(a, w ? &*w : nullptr);
                    std::cout << "replay alone: " << replay << "\n" << wl << "\n";
                    std::fflush(stdout);
                }
                cases.push_back({"regress." + p.name, caseName, r.rtlSeconds + r.goldenSeconds + r.referenceSeconds,
                                 !r.passed, std::to_string(r.mismatches) + " mismatches",
                                 r.scoreboard + (r.passed ? "" : "replay alone: " + replay + "\n" + wl + "\n")});
                all.push_back(hwJson(path, p, "rtl", r, scene.camera.width, scene.camera.height));
                if (reseeded) all.back()["sim_seed"] = seed;
                if (!r.passed) all.back()["replay"] = replay;
                if (w) all.back()["waves"] = {{"file", w->file}, {"cycle", w->cycle}, {"start", w->start}, {"end", w->end}};
                if (!a.images.empty()) {
                    const fs::path dir = fs::path(a.images) / stem / p.name;
                    fs::create_directories(dir);
                    writeImage(r.hardware, (dir / "rtl.png").string());
                    writeImage(r.reference, (dir / "reference.png").string());
                    writeImage(r.difference, (dir / "difference.png").string());
                }
                progress.step(stem + "/" + p.name);
            }
        }
    }
    progress.finish();
    if (!a.out.empty()) {
        nlohmann::json doc = provenance();
        doc["runs"] = all;
        writeTextFile(a.out, doc.dump(2) + "\n");
    }
    if (!a.junit.empty()) writeJunit(a.junit, "pst regress", cases, junitProperties());
    std::printf("%s: %zu runs, %d failed", failures ? "FAILED" : "PASSED", all.size(), failures);
    if (skipped) std::printf(", %d skipped (no hardware unit for their noise basis)", skipped);
    if (reseeded) {
        std::printf(" (sim seeds");
        for (uint64_t s : a.seeds) std::printf(" %llu", (unsigned long long)s);
        std::printf(")");
    }
    std::printf("\n");
    return failures ? 1 : 0;
}

}  // namespace pst::cli
