// pst render SCENE [--profile P]: filtered, unfiltered, filter-width (and ground-truth) images +
// report; with --profile the same scene through the RTL (and golden) model of profile P.
#include <chrono>
#include <iostream>
#include <memory>
#include <sstream>

#include "common.h"
#include "imageio.h"
#include "provenance.h"

namespace pst::cli {
namespace {

struct RenderArgs {
    std::string scene, outDir;
    int size = 0, width = 0, height = 0, truth = 0, threads = 0;
    uint64_t seed = 1;
    bool quiet = false;
    std::string bandlimit;    // every texture's bandlimit (parseBandlimit's names)
    std::string filter;       // every texture's filter kind (parseFilterKind's names)
    std::string widthCap;     // every texture's width cap ("on" / "off")
    std::vector<std::string> variants;  // extra filtered images (parseVariant's spellings)
};

int runHardwareRender(const RenderArgs& a, const HwArgs& hw) {
    const int w = a.size ? a.size : a.width, h = a.size ? a.size : a.height;
    Scene scene = loadScene(a.scene, w, h);
    overrideTextures(scene, a.bandlimit, a.filter, a.widthCap);
    const std::string stem = fs::path(a.scene).stem().string();
    int rc = 0;
    std::vector<std::string> pageArgs;
    // Every profile is loaded and checked before anything is written (a bad second profile
    // must not leave the first one's images behind).
    std::vector<Profile> profiles;
    for (const std::string& name : hw.profiles) {
        profiles.push_back(profileByName(name, hw.model == "rtl"));
        if (std::string why = unsupportedTexture(scene, profiles.back()); !why.empty()) throw InputError(why);
    }
    if (!hw.trace.empty()) checkTracePath(hw.trace);
    // One output transaction: every profile's folder, the trace and the page, or none of them.
    Outputs outputs;
    std::vector<fs::path> dirs, staged;
    for (const Profile& p : profiles) {
        dirs.push_back(a.outDir.empty() ? fs::path("out") / stem / p.name
                                        : (hw.profiles.size() > 1 ? fs::path(a.outDir) / p.name : fs::path(a.outDir)));
        staged.push_back(outputs.dir("-o", dirs.back().string()));
    }
    const std::string trace = outputs.file("--trace", hw.trace);
    const std::string page = outputs.file("--html", hw.html);
    for (size_t pi = 0; pi < profiles.size(); ++pi) {
        const Profile& p = profiles[pi];
        const fs::path& dir = dirs[pi];
        std::unique_ptr<RtlModel> rtl;
        if (hw.model == "rtl") {
            SimOptions so = hw.sim;
            if (!trace.empty()) so.traceFile = trace;
            rtl = makeRtlModel(p.name, so);
        }
        HwRenderOptions ho;
        ho.progress = progressPrinter(stem + "/" + p.name, a.quiet);
        ho.truthSamples = a.truth;
        HwRenderResult r = renderHardware(scene, p, rtl.get(), ho);
        const bool ranRtl = rtl != nullptr;
        rtl.reset();   // closes the trace
        const fs::path out = staged[pi];
        writeImage(r.hardware, (out / (hw.model + ".png")).string());
        writeImage(r.reference, (out / "reference.png").string());
        writeImage(r.difference, (out / "difference.png").string());
        writeTextFile((out / "summary.json").string(),
                      withProvenance(hwJson(a.scene, p, hw.model, r, scene.camera.width, scene.camera.height)).dump(2) +
                          "\n");
        pageArgs.insert(pageArgs.end(), {"--summary", (out / "summary.json").string()});
        std::cout << stem << " [" << p.name << ", " << hw.model << "]: " << r.fragments << " fragments";
        if (ranRtl) std::cout << ", " << r.mismatches << " mismatches, " << r.cyclesPerPixel << " cycles/pixel";
        std::cout << ", PSNR vs reference " << r.vsReference.psnr << " dB, " << r.vsReference.within1Lsb
                  << "% within 1 LSB -> " << dir.string() << "\n";
        for (const auto& n : r.notes) std::cout << "  note: " << n << "\n";
        if (ranRtl && !r.passed) {
            std::cout << r.scoreboard;
            rc = 1;
        }
    }
    commitWithPage(outputs, page, hw.html, pageArgs);
    return rc;
}

int runRender(const RenderArgs& a) {
    const int w = a.size ? a.size : a.width, h = a.size ? a.size : a.height;
    Scene scene = loadScene(a.scene, w, h);
    overrideTextures(scene, a.bandlimit, a.filter, a.widthCap);
    const std::string stem = fs::path(a.scene).stem().string();
    const fs::path dir = a.outDir.empty() ? fs::path("out") / stem : fs::path(a.outDir);

    RenderOptions opt;
    opt.truthSamples = a.truth;
    opt.seed = a.seed;
    opt.threads = a.threads;
    opt.progress = progressPrinter(stem, a.quiet);
    opt.variants = parseVariants(a.variants);
    checkVariants(scene, opt.variants);
    Outputs outputs;   // every file, or none
    const fs::path staged = outputs.dir("-o", dir.string());
    auto out = [&staged](const std::string& name) { return (staged / name).string(); };
    const auto t0 = std::chrono::steady_clock::now();
    RenderResult r = render(scene, opt);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    writeImage(r.filtered, out("filtered.png"));
    writeImage(r.filtered, out("filtered.exr"));
    writeImage(r.unfiltered, out("unfiltered.png"));
    writeImage(r.filterWidth, out("width.png"), Tone::FilterWidth);
    writeImage(r.filterWidth, out("width.exr"), Tone::FilterWidth);

    nlohmann::json j;
    j["scene"] = a.scene;
    j["title"] = scene.title;
    j["filter"] = a.filter;
    j["bandlimit"] = a.bandlimit;
    j["width"] = scene.camera.width;
    j["height"] = scene.camera.height;
    j["fragments"] = r.stats.fragments;
    j["seconds"] = {{"total", seconds}, {"raster", r.stats.rasterSeconds},
                    {"shade", r.stats.shadeSeconds}, {"truth", r.stats.truthSeconds}};
    std::ostringstream line;
    line << stem << ": " << scene.camera.width << "x" << scene.camera.height << ", "
         << r.stats.fragments << " fragments, " << seconds << " s";
    if (a.truth > 0) {
        writeImage(r.truth, out("truth.png"));
        writeImage(r.truth, out("truth.exr"));
        const ImageDiff df = compareRgb(r.filtered, r.truth), du = compareRgb(r.unfiltered, r.truth);
        j["truth_samples"] = a.truth * a.truth;
        j["vs_truth"] = {{"filtered", {{"rms", df.rmsError}, {"psnr", df.psnr}, {"max", df.maxError}}},
                         {"unfiltered", {{"rms", du.rmsError}, {"psnr", du.psnr}, {"max", du.maxError}}}};
        line << ", RMS vs truth: filtered " << df.rmsError << ", unfiltered " << du.rmsError;
    }
    // Variants: every texture's filter and bandlimit replaced (variant_<name>.png).
    for (size_t v = 0; v < opt.variants.size(); ++v) {
        const FilterVariant& fv = opt.variants[v];
        writeImage(r.variants[v], out("variant_" + fv.name + ".png"));
        nlohmann::json e = {{"filter", toString(fv.filter)}, {"bandlimit", toString(fv.bandlimit)}};
        if (a.truth > 0) {
            const ImageDiff d = compareRgb(r.variants[v], r.truth);
            e["vs_truth"] = {{"rms", d.rmsError}, {"psnr", d.psnr}, {"max", d.maxError}};
            line << ", " << fv.name << " " << d.rmsError;
        }
        j["variants"][fv.name] = e;
    }
    writeTextFile(out("report.json"), withProvenance(j).dump(2) + "\n");
    outputs.commit();
    std::cout << line.str() << " -> " << dir.string() << "\n";
    return 0;
}

}  // namespace

Command registerRender(CLI::App& app) {
    auto ra = std::make_shared<RenderArgs>();
    auto hw = std::make_shared<HwArgs>();
    auto* render = app.add_subcommand("render", "Render a scene through the reference model");
    render->add_option("scene", ra->scene, "Scene file (TOML, see scenes/README.md)")->required()->check(CLI::ExistingFile);
    render->add_option("-o,--out", ra->outDir, "Output folder (default out/<scene name>)");
    render->add_option("--size", ra->size, "Square image size, overrides the scene's (0: the scene's)")->check(CLI::Range(1, 16384));
    render->add_option("--width", ra->width, "Image width, overrides the scene's (0: the scene's)")->check(CLI::Range(1, 16384));
    render->add_option("--height", ra->height, "Image height, overrides the scene's (0: the scene's)")->check(CLI::Range(1, 16384));
    render->add_option("--truth", ra->truth, "Also render the ground truth with N x N jittered samples per pixel (0: none)")->check(CLI::Range(1, 64));
    render->add_option("--seed", ra->seed, "Jitter seed of the ground truth");
    render->add_option("-j,--threads", ra->threads, "Threads (0: all cores)")->check(CLI::Range(0, 256));
    render->add_flag("-q,--quiet", ra->quiet, "No progress on stderr");
    addTextureOverrideOptions(render, ra->bandlimit, ra->filter, ra->widthCap);
    render->add_option("--variants", ra->variants, "Also the filtered image with every texture's filter (and bandlimit) "
                       "replaced, per KIND[+BANDLIMIT] (e.g. trapezoid sat+footprint), compared with the truth (reference only)")
        ->delimiter(',');
    addProfileOptions(render, hw->profiles, hw->model, "Hardware profile(s): renders through the RTL");
    render->add_option("--trace", hw->trace, "FST waveform of the RTL run (off unless given)");
    render->add_option("--trace-start", hw->sim.traceStart, "First traced cycle");
    render->add_option("--trace-end", hw->sim.traceEnd, "Last traced cycle");
    render->add_option("--html", hw->html, "With --profile: also an HTML page of the runs (table, image viewer)");
    addSimOptions(render, *hw);
    return {render, [ra, hw, render]() {
                if (!hw->html.empty() && hw->profiles.empty()) throw InputError("--html: needs --profile");
                checkTraceOptions(render, hw->trace, hw->profiles, hw->model, {"--trace-start", "--trace-end"});
                checkTraceWindow(hw->sim);
                refuseHardwareOptionsWithoutModel(render, *hw);
                checkOutFolder(ra->outDir);
                checkNotInput("--trace", hw->trace, {ra->scene});
                checkNotInput("--html", hw->html, {ra->scene});
                checkCreatableFileDir("--html", hw->html);
                checkNotFolder("--html", hw->html);
                return hw->profiles.empty() ? runRender(*ra) : runHardwareRender(*ra, *hw);
            }};
}

}  // namespace pst::cli
