// pst atlas SCENE: texture-atlas mode (atlas_cmd.h), the options and the steps in order.
#include <fstream>
#include <iostream>
#include <memory>

#include "atlas_cmd.h"
#include "provenance.h"

namespace pst::cli {
namespace {

// "FILE:LINE" of the k-th [[objects]] table of a scene file ("FILE" if not found).
std::string objectWhere(const std::string& path, int k) {
    std::ifstream in(path);
    std::string line;
    int n = -1;
    for (int no = 1; std::getline(in, line); ++no) {
        const size_t a = line.find_first_not_of(" \t");
        if (a != std::string::npos && line.compare(a, 11, "[[objects]]") == 0 && ++n == k)
            return path + ":" + std::to_string(no);
    }
    return path;
}

// The use of each object's mesh edges (atlas triangles grouped by object; index = object).
std::vector<MeshEdges> objectEdges(const Scene& scene, const std::vector<AtlasTriangle>& tris) {
    std::vector<std::vector<AtlasTriangle>> byObject(scene.objects.size());
    for (const AtlasTriangle& t : tris) byObject[size_t(t.object)].push_back(t);
    std::vector<MeshEdges> out;
    for (const auto& ts : byObject) {
        MeshEdges m = meshEdges(ts);
        // The triangle named by its index in the object's mesh, not in this object's list.
        if (m.firstNonManifold >= 0) m.firstNonManifold = ts[size_t(m.firstNonManifold)].index;
        out.push_back(m);
    }
    return out;
}

// --mip pairs triangles across their edges: refuses an object with an edge on three or more
// triangles ("FILE:LINE: FIELD: ..." of its mesh key, or of its OBJ file). Open edges pass: a
// boundary triangle only has fewer neighbours in the dual graph.
void refuseNonManifold(const Scene& scene, const std::vector<MeshEdges>& edges) {
    for (size_t o = 0; o < edges.size(); ++o) {
        const MeshEdges& m = edges[o];
        if (m.nonManifold == 0) continue;
        throw InputError(scene.objects[o].meshSource + ": " + std::to_string(m.nonManifold) +
                         (m.nonManifold == 1 ? " edge" : " edges") + " on 3 or more triangles (non-manifold; up to " +
                         std::to_string(m.mostTriangles) + " on one edge, the first at triangle " +
                         std::to_string(m.firstNonManifold) +
                         "); --mip pairs triangles across their shared edges, which needs every edge on at most two "
                         "triangles (the strip atlases, without --mip, take this mesh)");
    }
}

// Step 1: the triangles (a zero-area one has no chart) and the atlas (section 4).
AtlasLayout buildLayout(const AtlasArgs& a, const Scene& scene, const AtlasOptions& options) {
    AtlasLayout L;
    L.options = options;
    const std::vector<AtlasTriangle> tris = sceneTriangles(scene);
    for (const AtlasTriangle& t : tris) {
        const double e = t.longestEdge();
        if (!(t.area() > 1e-12 * e * e))
            throw InputError(objectWhere(a.scene, t.object) + ": objects[" + std::to_string(t.object) +
                             "].mesh: triangle " + std::to_string(t.index) + " of '" + scene.objects[size_t(t.object)].name +
                             "' has zero area (degenerate; check the object's scale)");
    }
    const std::vector<MeshEdges> edges = objectEdges(scene, tris);
    if (a.mip) refuseNonManifold(scene, edges);
    for (const MeshEdges& m : edges) L.openEdges += m.open, L.nonManifoldEdges += m.nonManifold;
    L.atlas = a.mip ? buildMultiresAtlas(tris, L.options) : buildAtlas(tris, L.options);
    AtlasOptions std0 = L.options;
    std0.seamFree = false;
    L.standard = a.mip ? buildMultiresAtlas(tris, std0) : buildAtlas(tris, std0);
    L.minLegs = 1 << 30;
    for (const Chart& c : L.atlas.charts) L.minLegs = std::min(L.minLegs, c.legs), L.maxLegs = std::max(L.maxLegs, c.legs);
    L.owners = L.atlas.owners();
    L.stdOwners = L.standard.owners();
    return L;
}

// Step 2: the fill (one fragment per texel), through the profile's models when given.
AtlasFill fillStep(const AtlasArgs& a, const HwArgs& hw, const Scene& scene, const AtlasLayout& L,
                   const std::optional<Profile>& prof) {
    if (!prof) return fillAtlasReference(scene, L.atlas, a.threads);
    std::unique_ptr<RtlModel> rtl;
    if (hw.model == "rtl") rtl = makeRtlModel(prof->name, hw.sim);
    return fillAtlas(scene, L.atlas, *prof, rtl.get());
}

// Step 3: the view texture-mapped with the atlas; seams; the per-pixel render and the truth.
AtlasViews renderStep(const AtlasArgs& a, const Scene& scene, const AtlasLayout& L, const AtlasFill& fill, bool hardware,
                      const GpuFill* gpu) {
    AtlasViews v;
    v.nearest = renderWithAtlas(scene, L.atlas, fill.reference, L.owners, Magnification::Nearest);
    v.bilinear = renderWithAtlas(scene, L.atlas, fill.reference, L.owners, Magnification::Bilinear);
    const Image blank(L.standard.size(), L.standard.size(), 4);
    v.stdNearest = renderWithAtlas(scene, L.standard, blank, L.stdOwners, Magnification::Nearest);
    v.stdBilinear = renderWithAtlas(scene, L.standard, blank, L.stdOwners, Magnification::Bilinear);
    RenderOptions ro;
    ro.truthSamples = a.truth;
    ro.threads = a.threads;
    v.perPixel = render(scene, ro);
    const Image& truth = v.perPixel.truth;
    v.dN = compareRgb(v.nearest.image, truth);
    v.dB = compareRgb(v.bilinear.image, truth);
    v.dP = compareRgb(v.perPixel.filtered, truth);
    v.dBP = compareRgb(v.bilinear.image, v.perPixel.filtered);
    if (hardware) v.hwBilinear = renderWithAtlas(scene, L.atlas, fill.hardware, L.owners, Magnification::Bilinear);
    if (gpu) v.gpuBilinear = renderWithAtlas(scene, L.atlas, gpu->image, L.owners, Magnification::Bilinear);
    if (a.mip) {
        v.trilinear = renderWithAtlasTrilinear(scene, L.atlas, mipLevels(fill.reference, L.owners));
        v.mixing = mipMixing(L.atlas, dualGraph(L.atlas.triangles));
    }
    return v;
}

// Step 6: every file, into the output transaction's folder `dir` (moved into place by the commit).
void writeStep(const AtlasArgs& a, const HwArgs& hw, const fs::path& dir, const Scene& scene, const AtlasLayout& L,
               const AtlasViews& v, const AtlasFill& fill, bool hardware, const GpuFill* gpu, const Turntable& turn,
               const nlohmann::json& j, const std::string& md) {
    auto out = [&dir](const std::string& name) { return (dir / name).string(); };
    writeImage(fill.reference, out("atlas.png"));
    if (hardware) writeImage(fill.hardware, out("atlas_" + hw.model + ".png"));
    if (gpu) {
        writeImage(gpu->image, out("atlas_gpu.png"));
        writeImage(v.gpuBilinear.image, out("render_gpu_bilinear.png"));
    }
    writeImage(v.nearest.image, out("render_nearest.png"));
    writeImage(v.bilinear.image, out("render_bilinear.png"));
    if (a.mip) writeImage(v.trilinear.image, out("render_trilinear.png"));
    writeImage(v.perPixel.filtered, out("per_pixel.png"));
    writeImage(v.perPixel.truth, out("truth.png"));
    writeImage(relativeScalePicture(scene, L.atlas), out("scale.png"));
    if (!turn.frames.empty()) fs::create_directories(dir / "turntable");
    for (const auto& [name, img] : turn.frames) writeImage(img, out(name));
    writeTextFile(out("atlas.json"), withProvenance(j).dump(2) + "\n");
    writeTextFile(out("atlas.md"), md);
}

int runAtlas(const AtlasArgs& a, const HwArgs& hw) {
    AtlasOptions ao;
    if (!parseAtlasKind(a.kind, &ao.kind)) throw InputError("--atlas: '" + a.kind + "' is not uniform, area or length");
    if (!parseMagnification(a.magnification, &ao.magnification))
        throw InputError("--magnification: '" + a.magnification + "' is not nearest or bilinear");
    ao.size = a.size;
    if (hw.profiles.size() > 1) throw InputError("--profile: atlas takes one profile");
    const bool onGpu = a.filler == "gpu";
    if (onGpu && !hw.profiles.empty())
        throw InputError("--filler gpu: refuses --profile (one filler beside the host reference per run: the chip's "
                         "with --profile, or the GPU's)");
    const Scene scene = opaqueLayer(loadScene(a.scene, a.image, a.image));
    const std::string stem = fs::path(a.scene).stem().string();
    const fs::path dir = a.outDir.empty() ? fs::path("out") / "atlas" / stem : fs::path(a.outDir);
    Outputs outputs;   // every file, or none
    const fs::path staged = outputs.dir("-o", dir.string());
    const AtlasLayout L = buildLayout(a, scene, ao);
    std::optional<Profile> prof;
    if (!hw.profiles.empty()) {
        prof = profileByName(hw.profiles[0], hw.model == "rtl");
        if (std::string why = unsupportedTexture(scene, *prof); !why.empty()) throw InputError(why);
    }
    auto say = [&](const std::string& s) {
        if (!a.quiet) std::fprintf(stderr, "%s: %s\n", stem.c_str(), s.c_str());
    };
    // The GPU first: its refusals (no EGL device, a basis it cannot stand for) before the host's work.
    std::optional<GpuFill> gpu;
    if (onGpu) {
        say("filling " + std::to_string(L.atlas.size()) + "^2 atlas on the GPU (multipass " + a.gpu.variant + ")");
        gpu = fillAtlasGpu(scene, L.atlas, a.gpu);
    }
    say("filling " + std::to_string(L.atlas.size()) + "^2 atlas");
    const AtlasFill fill = fillStep(a, hw, scene, L, prof);
    const GpuFill* g = gpu ? &*gpu : nullptr;
    say("rendering");
    const AtlasViews v = renderStep(a, scene, L, fill, prof.has_value(), g);
    // Step 4: the figures (atlas.json) and the summary line.
    std::ostringstream line;
    nlohmann::json j = atlasJson(a, L, v, fill, scene, line);
    int rc = 0;
    if (prof) rc = hardwareJson(hw, *prof, L, v, fill, j, line);
    if (gpu) rc = gpuJson(*gpu, v, fill, j, line);
    // Step 5: the turntable.
    Turntable turn;
    if (a.turntable > 1) {
        turn = runTurntable(a, scene, L, fill, say);
        turntableJson(a, turn, j, line);
    }
    const std::string md = atlasMarkdown(a, L, v, fill, prof, j);
    writeStep(a, hw, staged, scene, L, v, fill, prof.has_value(), g, turn, j, md);
    outputs.commit();
    std::cout << line.str() << " -> " << dir.string() << "\n";
    if (rc && prof) std::cout << fill.scoreboard;
    return rc;
}

}  // namespace

Command registerAtlas(CLI::App& app) {
    auto at = std::make_shared<AtlasArgs>();
    auto hw = std::make_shared<HwArgs>();
    auto* atlasCmd = app.add_subcommand("atlas", "Texture-atlas mode: fill a meshed atlas of the scene through the models, render with it");
    atlasCmd->add_option("scene", at->scene, "Scene file (its layer-0 objects)")->required()->check(CLI::ExistingFile);
    atlasCmd->add_option("--atlas", at->kind, "Atlas kind: uniform, area or length (Carr and Hart section 4)");
    atlasCmd->add_option("--size", at->size, "Atlas resolution H (H x H texels)")->check(CLI::Range(2, 4096));
    atlasCmd->add_flag("--mip", at->mip, "Multiresolution atlas of the --atlas kind (section 4.3, METIS quadtree; power-of-two "
                       "cells, per pair for area and length; --size a power of two) and a trilinear render");
    atlasCmd->add_option("--turntable", at->turntable, "Also N views turning about the target: the atlas render's "
                         "flicker against the per-pixel render's (temporal RMS vs the truth; 0: none)")->check(CLI::Range(2, 720));
    atlasCmd->add_option("--magnification", at->magnification, "Seam-free for: nearest or bilinear");
    atlasCmd->add_option("--image", at->image, "Square view size, overrides the scene's (0: the scene's)")->check(CLI::Range(1, 4096));
    atlasCmd->add_option("--truth", at->truth, "N x N jittered samples per pixel of the ground truth")->check(CLI::Range(1, 64));
    addProfileOptions(atlasCmd, hw->profiles, hw->model, "Also fill through this profile's golden model and RTL (scoreboarded)");
    atlasCmd->add_option("-o,--out", at->outDir, "Output folder (default out/atlas/<scene name>)");
    atlasCmd->add_option("-j,--threads", at->threads, "Threads (0: all cores)")->check(CLI::Range(0, 256));
    atlasCmd->add_flag("-q,--quiet", at->quiet, "No progress on stderr");
    atlasCmd->add_option("--filler", at->filler, "Who fills the atlas besides the host reference: host (only it) or gpu "
                         "(also the multipass pixel-shader noise of Hart 2001 on OpenGL ES 3 through EGL, docs/MULTIPASS.md; "
                         "the chip fills it with --profile)")->check(CLI::IsMember({"host", "gpu"}));
    atlasCmd->add_option("--variant", at->gpu.variant, "--filler gpu: the multipass program, sgi (section 4), rc (section 5, "
                         "register combiners) or xor (section 6.3, exclusive-or hash)")->check(CLI::IsMember({"sgi", "rc", "xor"}));
    atlasCmd->add_option("--bf", at->gpu.bf, "--filler gpu: fraction bits b_f of the 8-bit coordinates (b_i = 8 - b_f "
                         "integer bits: the noise repeats every 2^b_i lattice cells)")->check(CLI::Range(1, 7));
    addSimOptions(atlasCmd, *hw);
    return {atlasCmd, [at, hw, atlasCmd]() {
                refuseHardwareOptionsWithoutModel(atlasCmd, *hw);
                if (at->filler != "gpu") refuseGiven(atlasCmd, {"--variant", "--bf"}, "needs --filler gpu (the multipass GPU filler's option)");
                checkOutFolder(at->outDir);
                return runAtlas(*at, *hw);
            }};
}

}  // namespace pst::cli
