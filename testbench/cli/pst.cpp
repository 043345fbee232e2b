// pst: the project's one command-line tool.
//   pst render SCENE      filtered, unfiltered, filter-width (and ground-truth) images + report
//   pst eval              texture block + fragment file -> f, grad_s f, w, filtered RGBA
//   pst fragments SCENE   the rasterizer's fragment stream as a fragment file
//   pst compare A B       RMS / PSNR between two images
// Exit status: 0 success, 1 failure while running, 2 bad input or usage.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "fragments.h"
#include "imageio.h"
#include "render.h"
#include "scene.h"

namespace fs = std::filesystem;
using namespace pst;

namespace {

struct RenderArgs {
    std::string scene, outDir;
    int size = 0, width = 0, height = 0, truth = 0, threads = 0;
    uint64_t seed = 1;
    bool quiet = false;
};

// Progress on stderr: one rewritten line on a terminal, a line per stage otherwise.
std::function<void(const std::string&, double)> progressPrinter(const std::string& name, bool quiet) {
    if (quiet) return {};
    const bool tty = isatty(STDERR_FILENO);
    return [name, tty, last = std::string()](const std::string& stage, double frac) mutable {
        if (tty) {
            std::fprintf(stderr, "\r%s: %-6s %5.1f%%", name.c_str(), stage.c_str(), 100.0 * frac);
            if (frac >= 1.0) std::fprintf(stderr, "\n");
        } else if (frac >= 1.0 || stage != last) {
            if (frac >= 1.0) std::fprintf(stderr, "%s: %s done\n", name.c_str(), stage.c_str());
        }
        last = stage;
    };
}

int runRender(const RenderArgs& a) {
    const int w = a.size ? a.size : a.width, h = a.size ? a.size : a.height;
    Scene scene = loadScene(a.scene, w, h);
    const std::string stem = fs::path(a.scene).stem().string();
    const fs::path dir = a.outDir.empty() ? fs::path("out") / stem : fs::path(a.outDir);

    RenderOptions opt;
    opt.truthSamples = a.truth;
    opt.seed = a.seed;
    opt.threads = a.threads;
    opt.progress = progressPrinter(stem, a.quiet);
    const auto t0 = std::chrono::steady_clock::now();
    RenderResult r = render(scene, opt);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    fs::create_directories(dir);
    writeImage(r.filtered, (dir / "filtered.png").string());
    writeImage(r.filtered, (dir / "filtered.exr").string());
    writeImage(r.unfiltered, (dir / "unfiltered.png").string());
    writeImage(r.filterWidth, (dir / "width.png").string(), Tone::FilterWidth);
    writeImage(r.filterWidth, (dir / "width.exr").string(), Tone::FilterWidth);

    nlohmann::json j;
    j["scene"] = a.scene;
    j["title"] = scene.title;
    j["width"] = scene.camera.width;
    j["height"] = scene.camera.height;
    j["fragments"] = r.stats.fragments;
    j["seconds"] = {{"total", seconds}, {"raster", r.stats.rasterSeconds},
                    {"shade", r.stats.shadeSeconds}, {"truth", r.stats.truthSeconds}};
    std::ostringstream line;
    line << stem << ": " << scene.camera.width << "x" << scene.camera.height << ", "
         << r.stats.fragments << " fragments, " << seconds << " s";
    if (a.truth > 0) {
        writeImage(r.truth, (dir / "truth.png").string());
        writeImage(r.truth, (dir / "truth.exr").string());
        const ImageDiff df = compareRgb(r.filtered, r.truth), du = compareRgb(r.unfiltered, r.truth);
        j["truth_samples"] = a.truth * a.truth;
        j["vs_truth"] = {{"filtered", {{"rms", df.rmsError}, {"psnr", df.psnr}, {"max", df.maxError}}},
                         {"unfiltered", {{"rms", du.rmsError}, {"psnr", du.psnr}, {"max", du.maxError}}}};
        line << ", RMS vs truth: filtered " << df.rmsError << ", unfiltered " << du.rmsError;
    }
    writeTextFile((dir / "report.json").string(), j.dump(2) + "\n");
    std::cout << line.str() << " -> " << dir.string() << "\n";
    return 0;
}

int runEval(const std::string& texPath, const std::string& fragPath, const std::string& outPath,
            const std::string& filterName) {
    Texture tex = loadTexture(texPath);
    FilterKind kind = tex.filter;
    if (!filterName.empty() && !parseFilterKind(filterName, &kind))
        throw InputError("--filter: unknown filter '" + filterName + "' (expected none, mip, mip_linear, sat or box)");
    const auto frags = loadFragments(fragPath);
    std::ostringstream os;
    os << "# f  df/ds df/dt df/dr  w  r g b a   (texture " << texPath << ", filter " << toString(kind) << ")\n";
    char buf[512];
    for (const auto& fr : frags) {
        const TextureSample t = shade(tex, fr.s, fr.dsdx, fr.dsdy, kind);
        std::snprintf(buf, sizeof buf, "%.17g  %.17g %.17g %.17g  %.17g  %.17g %.17g %.17g %.17g\n", t.f,
                      t.gradS.x, t.gradS.y, t.gradS.z, t.filterWidth, t.rgba.r, t.rgba.g, t.rgba.b, t.rgba.a);
        os << buf;
    }
    if (outPath.empty() || outPath == "-") std::cout << os.str();
    else writeTextFile(outPath, os.str());
    return 0;
}

int runFragments(const std::string& scenePath, int size, int layer, const std::string& outPath) {
    Scene scene = loadScene(scenePath, size, size);
    if (layer < 0 || layer >= scene.layers())
        throw InputError("--layer: scene has layers 0.." + std::to_string(scene.layers() - 1));
    std::vector<FragmentRecord> recs;
    for (const auto& f : sceneFragments(scene, layer)) recs.push_back({f.s, f.dsdx, f.dsdy});
    std::ostringstream os;
    writeFragments(os, recs);
    if (outPath.empty() || outPath == "-") std::cout << os.str();
    else writeTextFile(outPath, os.str());
    return 0;
}

int runCompare(const std::string& a, const std::string& b) {
    const ImageDiff d = compareRgb(readImage(a), readImage(b));
    std::cout << "mean " << d.meanError << "  rms " << d.rmsError << "  max " << d.maxError
              << "  psnr " << d.psnr << " dB\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"pst: cycle-level simulator of the Hart et al. 1999 procedural solid-texturing ASIC"};
    app.require_subcommand(1);

    RenderArgs ra;
    auto* render = app.add_subcommand("render", "Render a scene through the reference model");
    render->add_option("scene", ra.scene, "Scene file (TOML, see scenes/README.md)")->required()->check(CLI::ExistingFile);
    render->add_option("-o,--out", ra.outDir, "Output folder (default out/<scene name>)");
    render->add_option("--size", ra.size, "Square image size, overrides the scene's")->check(CLI::Range(1, 16384));
    render->add_option("--width", ra.width, "Image width, overrides the scene's")->check(CLI::Range(1, 16384));
    render->add_option("--height", ra.height, "Image height, overrides the scene's")->check(CLI::Range(1, 16384));
    render->add_option("--truth", ra.truth, "Also render the ground truth with N x N jittered samples per pixel")->check(CLI::Range(1, 64));
    render->add_option("--seed", ra.seed, "Jitter seed of the ground truth");
    render->add_option("-j,--threads", ra.threads, "Threads (default: all cores)")->check(CLI::Range(0, 256));
    render->add_flag("-q,--quiet", ra.quiet, "No progress on stderr");

    std::string texPath, fragPath, evalOut, filterName;
    auto* eval = app.add_subcommand("eval", "Evaluate a texture at the fragments of a fragment file");
    eval->add_option("-t,--texture", texPath, "Texture block (TOML, the keys of [textures.NAME])")->required()->check(CLI::ExistingFile);
    eval->add_option("-f,--fragments", fragPath, "Fragment file: s t r ds/dx dt/dx dr/dx ds/dy dt/dy dr/dy per line")->required()->check(CLI::ExistingFile);
    eval->add_option("-o,--out", evalOut, "Output file (default stdout)");
    eval->add_option("--filter", filterName, "Override the texture's filter: none, mip, mip_linear, sat, box");

    std::string fragScene, fragOut;
    int fragSize = 0, fragLayer = 0;
    auto* frag = app.add_subcommand("fragments", "Write a scene's fragment stream as a fragment file");
    frag->add_option("scene", fragScene, "Scene file")->required()->check(CLI::ExistingFile);
    frag->add_option("--size", fragSize, "Square image size, overrides the scene's")->check(CLI::Range(1, 16384));
    frag->add_option("--layer", fragLayer, "Layer (0 = opaque pass)");
    frag->add_option("-o,--out", fragOut, "Output file (default stdout)");

    std::string cmpA, cmpB;
    auto* cmp = app.add_subcommand("compare", "RMS and PSNR between two images (RGB)");
    cmp->add_option("a", cmpA)->required()->check(CLI::ExistingFile);
    cmp->add_option("b", cmpB)->required()->check(CLI::ExistingFile);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    try {
        if (*render) return runRender(ra);
        if (*eval) return runEval(texPath, fragPath, evalOut, filterName);
        if (*frag) return runFragments(fragScene, fragSize, fragLayer, fragOut);
        if (*cmp) return runCompare(cmpA, cmpB);
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 2;
}
