// pst regress: every scene x every profile through the RTL (or --random fragments); non-zero
// exit on any mismatch. The options and the checks before any run; the modes are in
// regress_scenes.cpp and regress_random.cpp.
#include <algorithm>
#include <iostream>
#include <memory>
#include <random>

#include "regress.h"
#include "source_dir.h"

namespace pst::cli {

Unit unitByName(const std::string& name) {
    static const std::vector<std::pair<std::string, Unit>> units = {
        {"transform", Unit::Transform}, {"noise", Unit::Noise}, {"quadric", Unit::Quadric},
        {"accumulate", Unit::Accumulate}, {"filter_width", Unit::FilterWidth}, {"clut", Unit::ClutFilter}};
    for (const auto& [n, u] : units)
        if (n == name) return u;
    throw InputError("--inject-fault: '" + name + "' is not transform, noise, quadric, accumulate, filter_width or clut");
}

namespace {

struct RegressCli {
    RegressArgs a;
    HwArgs hw;
    RandomRegressOptions rnd;
    uint64_t rndCount = 0, reseed = 0;
    CLI::App* app = nullptr;
};

int run(RegressCli& c) {
    RegressArgs& a = c.a;
    HwArgs& hw = c.hw;
    CLI::App* regress = c.app;
    if (hw.profiles.empty()) hw.profiles = rtlProfiles();
    checkOutFile("-o", a.out);
    checkOutFile("--junit", a.junit);
    checkOutDir("--waves", a.waves);
    checkCreatableDir("--waves", a.waves);
    checkCreatableDir("--images", a.images);
    checkCreatableFileDir("--html", a.html);
    checkNotFolder("--html", a.html);
    for (const auto& [flag, out] : {std::pair<const char*, std::string>{"-o", a.out}, {"--junit", a.junit}, {"--html", a.html}})
        checkNotInput(flag, out, a.scenes);
    if (!a.out.empty()) checkNotInput("--junit", a.junit, {a.out});
    if (!a.injectFault.empty()) unitByName(a.injectFault);   // refused before any run
    if (a.injectAssert != UINT64_MAX) {
        std::vector<std::string> without;
        for (const auto& n : hw.profiles)
            if (!asserted(profileByName(n, true, false).name)) without.push_back(n);
        if (!without.empty())
            throw InputError("--inject-assert: profile '" + without[0] + "' is verilated here without assertions, so "
                             "the self-test cannot fire (configure with -DPST_SIM_ASSERT=ON, or give a test profile)");
    }
    // The seeds: one (--seed / --sim-seed, default 1), or --reseed N random ones, each printed.
    const bool random = c.rndCount > 0;
    if (c.reseed > 0) {
        if (random ? regress->count("--seed") : regress->count("--sim-seed"))
            throw InputError(std::string("--reseed: not with ") + (random ? "--seed" : "--sim-seed") + " (it draws the seeds)");
        if (!random && hw.sim.inputGapRate == 0 && hw.sim.outputStallRate == 0)
            throw InputError("--reseed: a scene run's only randomness is its input gaps and output stalls; give "
                             "--gap-rate or --stall-rate (or use --random)");
        std::random_device rd;
        std::mt19937_64 gen((uint64_t(rd()) << 32) ^ rd());
        for (uint64_t i = 0; i < c.reseed; ++i) a.seeds.push_back(gen() % 1000000000ULL + 1);
        for (uint64_t s : a.seeds) std::cout << "reseed: seed " << s << "\n";
    } else {
        a.seeds = {random ? c.rnd.seed : hw.sim.seed};
    }
    if (random) {
        if (!a.scenes.empty()) throw InputError("--random: takes no scene files");
        if (!a.images.empty()) throw InputError("--images: not with --random (it writes no images)");
        if (!a.html.empty()) throw InputError("--html: not with --random (it writes no images)");
        if (!a.waves.empty())
            throw InputError("--waves: not with --random (replay the failing segment with render --trace, or use scene mode)");
        if (regress->get_option("--size")->count()) throw InputError("--size: not with --random");
        refuseGiven(regress, kSimOptions, "not with --random (each random segment draws its own gaps and stalls from --seed)");
        if (c.rnd.from + c.rndCount > (uint64_t(1) << 32))
            throw InputError("--from: fragment indices are 32-bit tags (from + N <= 2^32)");
        c.rnd.fragments = c.rndCount;
        c.rnd.injectAssert = a.injectAssert;
        if (a.injectAssert != UINT64_MAX) {
            const std::vector<uint64_t> starts = segmentStarts(c.rnd);
            const uint64_t first = starts.empty() ? c.rnd.from : starts.front(), end = c.rnd.from + c.rndCount;
            if (a.injectAssert < first || a.injectAssert >= end)
                throw InputError("--inject-assert: fragment " + std::to_string(a.injectAssert) + " is outside the run "
                                 "(fragments " + std::to_string(first) + ".." + std::to_string(end - 1) +
                                 "); the self-test could not fire");
        }
        if (!a.injectFault.empty()) c.rnd.fault = unitByName(a.injectFault);
        if (a.list) {
            for (const auto& n : hw.profiles) std::cout << "profile " << profileByName(n, true, false).name << "\n";
            for (uint64_t s : segmentStarts(c.rnd)) std::cout << "segment " << s << "\n";
            return 0;
        }
        Outputs outputs;   // -o and --junit, or neither
        RegressArgs staged = a;
        staged.out = outputs.file("-o", a.out);
        staged.junit = outputs.file("--junit", a.junit);
        const int rc = runRegressRandom(staged, hw, c.rnd);
        outputs.commit();
        return rc;
    }
    if (a.scenes.empty()) {
        for (const auto& e : fs::directory_iterator(fs::path(sourceDir()) / "scenes"))
            if (e.path().extension() == ".toml") a.scenes.push_back(e.path().string());
        std::sort(a.scenes.begin(), a.scenes.end());
    }
    if (a.injectAssert != UINT64_MAX) hw.sim.busyWriteAfter = a.injectAssert + 1;
    if (a.list) {
        std::vector<std::string> names;
        for (const auto& n : hw.profiles) names.push_back(profileByName(n, true, false).name);
        for (const auto& sc : a.scenes)
            for (const auto& n : names) std::cout << sc << "\t" << n << "\n";
        return 0;
    }
    // --html: the JSON (default beside the page) and the images (default the page's folder) too.
    RegressArgs withPage = a;
    if (!a.html.empty()) {
        const fs::path page(a.html), dir = page.parent_path().empty() ? fs::path(".") : page.parent_path();
        if (withPage.out.empty()) withPage.out = (dir / (page.stem().string() + ".json")).string();
        if (withPage.images.empty()) withPage.images = dir.string();
    }
    // One output transaction: the images, the waves, -o, --junit and the page, or none of them.
    Outputs outputs;
    const std::string page = outputs.file("--html", a.html);   // first: a page that cannot be written is named as such
    RegressArgs staged = withPage;
    if (!withPage.images.empty()) staged.images = outputs.dir("--images", withPage.images);
    if (!withPage.waves.empty()) staged.waves = outputs.dir("--waves", withPage.waves);
    staged.wavesShown = withPage.waves;
    staged.out = outputs.file("-o", withPage.out);
    staged.junit = outputs.file("--junit", withPage.junit);
    const int rc = runRegressScenes(staged, hw);
    commitWithPage(outputs, page, a.html, {"--regress", staged.out, "--images", staged.images});
    return rc;
}

}  // namespace

Command registerRegress(CLI::App& app) {
    auto c = std::make_shared<RegressCli>();
    RegressArgs& a = c->a;
    HwArgs& hw = c->hw;
    auto* regress = app.add_subcommand("regress", "Every scene through every profile's RTL, checked against the golden model");
    c->app = regress;
    regress->add_option("scenes", a.scenes, "Scene files (default: scenes/*.toml)")->check(CLI::ExistingFile);
    regress->add_option("--size", a.size, "Square image size")->check(CLI::Range(1, 4096));
    regress->add_option("--profile", hw.profiles, profileHelp("Profiles (default: every verilated profile; one per --profile)"))
        ->allow_extra_args(false);
    regress->add_option("-o,--out", a.out, "JSON summary file (provenance and \"runs\")");
    regress->add_option("--junit", a.junit, "JUnit XML of the runs (one test case per scene x profile, or per profile with --random)");
    regress->add_option("--images", a.images, "Also write <dir>/<scene>/<profile>/{rtl,reference,difference}.png");
    regress->add_option("--html", a.html, "Also an HTML page: table, image viewer per scene (images to --images, "
                        "default the page's folder; JSON to -o, default beside the page)");
    addSimOptions(regress, hw);
    auto* rndOpt = regress->add_option("--random", c->rndCount, "Constrained-random mode: N random fragments per profile (random textures, gaps, stalls) instead of scenes (0: scene mode)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32));
    regress->add_option("--seed", c->rnd.seed, "Seed of --random")->needs(rndOpt);
    regress->add_option("--from", c->rnd.from, "Replay --random from the fragment with this index (starts at its segment)")->needs(rndOpt);
    regress->add_option("--batch", c->rnd.maxBatch, "Most fragments per random texture")->check(CLI::Range(1, 1 << 20))->needs(rndOpt);
    regress->add_flag("--probes", c->rnd.probes, "Sample the octave-stage probes in --random (names the first bad unit)")->needs(rndOpt);
    regress->add_option("--reseed", c->reseed, "Run everything with N random seeds (--seed of --random, else --sim-seed "
                        "with gaps or stalls), each printed (0: the one seed given)")
        ->check(CLI::Range(uint64_t(0), uint64_t(1000)));
    regress->add_flag("-q,--quiet", a.quiet, "No progress on stderr");
    regress->add_option("--waves", a.waves, "Folder for an FST of each failing scene run: the run again, traced from "
                        "--waves-before cycles before its first mismatch (or assertion) to --waves-after after it");
    regress->add_option("--waves-before", a.wavesBefore, "Cycles traced before the first failure")->check(CLI::Range(uint64_t(1), uint64_t(1) << 32));
    regress->add_option("--waves-after", a.wavesAfter, "Cycles traced after the first failure")->check(CLI::Range(uint64_t(0), uint64_t(1) << 32));
    regress->add_option("--inject-assert", a.injectAssert, "Self-test: once fragment I (of --random, or of each scene run) is in "
                        "the RTL, write a register while the pipeline is busy; the RTL's RegWriteOnlyWhenIdle assertion "
                        "must fire and fail the run (off unless given)")
        ->check(CLI::Range(uint64_t(0), (uint64_t(1) << 32) - 1));
    regress->add_option("--inject-fault", a.injectFault, "Self-test: perturb this golden-model unit (transform, noise, "
                        "quadric, accumulate, filter_width, clut) so that the scoreboard must report mismatches");
    regress->add_flag("--list", a.list, "Print the runs and exit (what scripts/regress.py splits into shards): "
                      "scene file TAB profile per line; with --random 'profile NAME' lines, then 'segment I' per "
                      "segment the run simulates (I: its first fragment)");
    return {regress, [c]() { return run(*c); }};
}

}  // namespace pst::cli
