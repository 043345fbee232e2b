// pst atlas: atlas.json, atlas.md and the turntable (atlas_cmd.h).
#include <cmath>
#include <fstream>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "animate.h"
#include "atlas_cmd.h"
#include "source_dir.h"

namespace pst::cli {
namespace {

// The profile's silicon clocks (MHz) as docs/data/silicon.json states them (scripts/gen_docs.py
// writes it from the silicon record, pstlib/report/silicon_table.py: the one place that picks
// the clock after layout): pre-layout, and after layout (the routed profile's post-route Fmax,
// any other's pre-layout Fmax derated by the synthesis); 0 where it has none.
struct SiliconClocks {
    double preLayout = 0;
    double afterLayout = 0;
};

SiliconClocks siliconClocks(const std::string& profile) {
    SiliconClocks c;
    std::ifstream in(sourceDir() + "/docs/data/silicon.json");
    if (!in) return c;
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.contains("profiles") || !j["profiles"].contains(profile)) return c;
    const auto& p = j["profiles"][profile];
    auto mhz = [&](const char* key) { return p.contains(key) && p[key].is_number() ? p[key].get<double>() : 0.0; };
    c.preLayout = mhz("fmax_mhz");
    c.afterLayout = mhz("fmax_layout_mhz");
    return c;
}

}  // namespace

nlohmann::json atlasJson(const AtlasArgs& a, const AtlasLayout& L, const AtlasViews& v, const AtlasFill& fill,
                         const Scene& scene, std::ostringstream& line) {
    const Atlas& atlas = L.atlas;
    nlohmann::json j;
    j["scene"] = a.scene;
    j["atlas"] = a.kind;
    j["size"] = atlas.size();
    j["magnification"] = a.magnification;
    j["triangles"] = atlas.triangles.size();
    j["eq3_edge"] = atlas.eq3Edge;
    j["legs"] = {{"min", L.minLegs}, {"max", L.maxLegs}};
    j["mesh_edges"] = {{"open", L.openEdges}, {"non_manifold", L.nonManifoldEdges}};
    j["strips"] = atlas.stripCount;
    j["coverage"] = coverage(atlas);
    j["relative_scale"] = relativeScale(atlas);
    j["texel_use"] = texelUse(atlas);
    j["standard_layout"] = {{"coverage", coverage(L.standard)}, {"relative_scale", relativeScale(L.standard)}};
    j["paper_table1_rhino"] = {{"uniform", {0.91, 1.75}}, {"area", {0.93, 0.66}}, {"length", {0.93, 0.86}}};
    j["image"] = {{"width", scene.camera.width}, {"height", scene.camera.height}, {"truth_samples", a.truth * a.truth}};
    j["seams"] = {{"pixels", v.bilinear.pixels},
                  {"nearest", v.nearest.seamPixels}, {"bilinear", v.bilinear.seamPixels},
                  {"standard_nearest", v.stdNearest.seamPixels}, {"standard_bilinear", v.stdBilinear.seamPixels}};
    j["rms_vs_truth"] = {{"atlas_nearest", v.dN.rmsError}, {"atlas_bilinear", v.dB.rmsError}, {"per_pixel", v.dP.rmsError}};
    j["rms_atlas_bilinear_vs_per_pixel"] = v.dBP.rmsError;
    if (a.mip) {
        const double dT = compareRgb(v.trilinear.image, v.perPixel.truth).rmsError;
        j["rms_vs_truth"]["atlas_trilinear"] = dT;
        int minCell = atlas.mipCell;
        for (const Chart& c : atlas.charts) minCell = std::min(minCell, atlas.cellSize(c.legs).x);
        j["mip"] = {{"cell", atlas.mipCell}, {"cell_min", minCell}, {"levels", v.mixing.size()}, {"mixing_texels", v.mixing}};
    }
    j["fill"] = {{"texels", fill.texels}, {"reference_seconds", fill.referenceSeconds},
                 {"texels_per_second", fill.referenceSeconds > 0 ? double(fill.texels) / fill.referenceSeconds : 0.0}};
    const std::string stem = fs::path(a.scene).stem().string();
    line << stem << " " << a.kind << " " << atlas.size() << ": C " << coverage(atlas) << ", S " << relativeScale(atlas)
         << ", seams nearest " << v.nearest.seamPixels << " bilinear " << v.bilinear.seamPixels << " (standard layout "
         << v.stdNearest.seamPixels << " / " << v.stdBilinear.seamPixels << "), RMS vs truth: atlas " << v.dN.rmsError
         << " / " << v.dB.rmsError;
    if (a.mip) line << " / trilinear " << j["rms_vs_truth"]["atlas_trilinear"].get<double>();
    line << ", per pixel " << v.dP.rmsError;
    return j;
}

int hardwareJson(const HwArgs& hw, const Profile& prof, const AtlasLayout& L, const AtlasViews& v,
                 const AtlasFill& fill, nlohmann::json& j, std::ostringstream& line) {
    int rc = 0;
    const SiliconClocks clocks = siliconClocks(prof.name);
    const double fmax = clocks.preLayout;
    nlohmann::json f = {{"profile", prof.name}, {"model", hw.model}, {"texels", fill.texels},
                        {"golden_seconds", fill.goldenSeconds}, {"notes", fill.notes},
                        {"vs_reference", {{"rms", compareRgb(fill.hardware, fill.reference).rmsError}}},
                        {"render_bilinear_rms_vs_truth", compareRgb(v.hwBilinear.image, v.perPixel.truth).rmsError}};
    if (hw.model == "rtl") {
        f["passed"] = fill.passed;
        f["mismatches"] = fill.mismatches;
        f["cycles"] = fill.cycles;
        f["cycles_per_texel"] = fill.texels ? double(fill.cycles) / double(fill.texels) : 0.0;
        f["rtl_seconds"] = fill.rtlSeconds;
        f["gap_rate"] = hw.sim.inputGapRate;
        f["stall_rate"] = hw.sim.outputStallRate;
        f["fmax_mhz"] = fmax > 0 ? nlohmann::json(fmax) : nlohmann::json(nullptr);
        f["fill_ms_at_fmax"] = fmax > 0 ? nlohmann::json(double(fill.cycles) / (fmax * 1e3)) : nlohmann::json(nullptr);
        const double fmaxLayout = fmax > 0 ? clocks.afterLayout : 0;
        if (fmaxLayout > 0) {
            f["fmax_layout_mhz"] = fmaxLayout;
            f["fill_ms_at_layout_fmax"] = double(fill.cycles) / (fmaxLayout * 1e3);
        }
        // Carr and Hart's Table 3: host synthesis rates (Hz) of 1 and 4 octaves at this size.
        const std::map<int, std::pair<double, double>> table3 = {{256, {9.09, 6.25}}, {512, {2.56, 1.82}},
                                                                 {1024, {0.72, 0.40}}};
        if (auto it = table3.find(L.atlas.size()); it != table3.end())
            f["paper_table3_host_hz"] = {{"octaves_1", it->second.first}, {"octaves_4", it->second.second}};
        if (fmax > 0 && fill.cycles > 0) f["fill_hz_at_fmax"] = fmax * 1e6 / double(fill.cycles);
        line << "; " << prof.name << " RTL " << fill.mismatches << " mismatches, " << fill.cycles << " cycles";
        if (fmax > 0) line << " = " << double(fill.cycles) / (fmax * 1e3) << " ms at " << fmax << " MHz";
        if (!fill.passed) rc = 1;
    }
    j["hardware"] = f;
    return rc;
}

int gpuJson(const GpuFill& g, const AtlasViews& v, const AtlasFill& fill, nlohmann::json& j, std::ostringstream& line) {
    const double rmsRef = compareRgb(g.image, fill.reference).rmsError;
    const double renderTruth = compareRgb(v.gpuBilinear.image, v.perPixel.truth).rmsError;
    const double renderPerPixel = compareRgb(v.gpuBilinear.image, v.perPixel.filtered).rmsError;
    j["gpu"] = {{"variant", g.variant}, {"interp", g.interp}, {"b", g.b}, {"b_f", g.bf}, {"b_i", g.b - g.bf},
                {"arith", "shader"}, {"renderer", g.renderer}, {"gl_version", g.glVersion}, {"egl_platform", g.eglPlatform},
                {"on_gpu", "every octave's noise n(T_i s) (the multipass program, one draw per pass)"},
                {"on_host", "T_i s quantized to b_i.b_f bytes, f = q(s) + sum_i a_i (n_i - 1/2), the colour map's point sample"},
                {"texels", g.texels}, {"octaves", g.octaves}, {"draws_per_octave", g.drawsPerOctave}, {"draws", g.draws},
                {"seconds", g.seconds}, {"pass_seconds", g.passSeconds},
                {"texels_per_second", g.seconds > 0 ? double(g.texels) / g.seconds : 0.0},
                {"texels_per_second_passes", g.passSeconds > 0 ? double(g.texels) / g.passSeconds : 0.0},
                {"cpu_model", {{"noise_values", g.noiseValues}, {"mismatches", g.cpuModelMismatches},
                               {"seconds", g.cpuModelSeconds}}},
                {"vs_reference", {{"rms", rmsRef}}},
                {"render_bilinear_rms_vs_truth", renderTruth},
                {"render_bilinear_rms_vs_per_pixel", renderPerPixel},
                {"notes", g.notes}};
    line << "; GPU " << g.variant << " (" << g.draws << " draws, " << g.octaves << " octaves) "
         << (g.seconds > 0 ? double(g.texels) / g.seconds : 0.0) << " texels/s, " << g.cpuModelMismatches
         << " values differing from the CPU model, RMS vs truth " << renderTruth << ", vs per pixel " << renderPerPixel;
    return g.cpuModelMismatches == 0 ? 0 : 1;
}

// The turntable: the camera turned about its up axis through the target, the atlas (filled
// once: it is view-independent) against the per-pixel render, both against the truth;
// flicker = mean temporal RMS against the truth's own change (animate.h temporalRms).
Turntable runTurntable(const AtlasArgs& a, const Scene& scene, const AtlasLayout& L, const AtlasFill& fill,
                       const std::function<void(const std::string&)>& say) {
    Turntable t;
    RenderOptions ro;
    ro.truthSamples = a.truth;
    ro.threads = a.threads;
    std::vector<Image> prevA, prevP, prevT, prevM;
    const std::vector<Image> levels = a.mip ? mipLevels(fill.reference, L.owners) : std::vector<Image>();
    const int n = a.turntable;
    for (int k = 0; k < n; ++k) {
        throwIfInterrupted();   // SIGINT, SIGTERM: between frames
        say("turntable frame " + std::to_string(k + 1) + "/" + std::to_string(n));
        Scene v = scene;
        const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), 2.0 * M_PI * k / n, scene.camera.up);
        v.camera.eye = scene.camera.target + glm::dvec3(turn * glm::dvec4(scene.camera.eye - scene.camera.target, 0.0));
        const AtlasRender ar = renderWithAtlas(v, L.atlas, fill.reference, L.owners, Magnification::Bilinear);
        const RenderResult pr = render(v, ro);
        t.rmsA += compareRgb(ar.image, pr.truth).rmsError / n;
        t.rmsP += compareRgb(pr.filtered, pr.truth).rmsError / n;
        Image mr;
        if (a.mip) {
            mr = renderWithAtlasTrilinear(v, L.atlas, levels).image;
            t.rmsM += compareRgb(mr, pr.truth).rmsError / n;
            if (k > 0) t.flM += temporalRms(prevM[0], mr, prevT[0], pr.truth) / (n - 1);
            prevM = {mr};
        }
        if (k > 0) {
            t.flA += temporalRms(prevA[0], ar.image, prevT[0], pr.truth) / (n - 1);
            t.flP += temporalRms(prevP[0], pr.filtered, prevT[0], pr.truth) / (n - 1);
        }
        char name[64];
        std::snprintf(name, sizeof name, "frame_%04d.png", k);
        t.frames.push_back({std::string("turntable/atlas_") + name, ar.image});
        t.frames.push_back({std::string("turntable/per_pixel_") + name, pr.filtered});
        prevA = {ar.image};
        prevP = {pr.filtered};
        prevT = {pr.truth};
    }
    return t;
}

void turntableJson(const AtlasArgs& a, const Turntable& t, nlohmann::json& j, std::ostringstream& line) {
    j["turntable"] = {{"frames", a.turntable},
                      {"flicker", {{"atlas_bilinear", t.flA}, {"per_pixel", t.flP}}},
                      {"rms_vs_truth_mean", {{"atlas_bilinear", t.rmsA}, {"per_pixel", t.rmsP}}}};
    if (a.mip) {
        j["turntable"]["flicker"]["atlas_trilinear"] = t.flM;
        j["turntable"]["rms_vs_truth_mean"]["atlas_trilinear"] = t.rmsM;
    }
    line << "; turntable " << a.turntable << " frames: flicker atlas " << t.flA;
    if (a.mip) line << " / trilinear " << t.flM;
    line << ", per pixel " << t.flP;
}

std::string atlasMarkdown(const AtlasArgs& a, const AtlasLayout& L, const AtlasViews& v, const AtlasFill& fill,
                          const std::optional<Profile>& prof, const nlohmann::json& j) {
    const Atlas& atlas = L.atlas;
    const AtlasKind kind = L.options.kind;
    const std::string stem = fs::path(a.scene).stem().string();
    std::ostringstream md;
    md << "# Atlas: " << stem << " (" << a.kind << ", " << atlas.size() << " x " << atlas.size() << ", seam-free for "
       << a.magnification << ")\n\n"
       << "| measure | ours | paper Table 1 (rhino, " << a.kind << ") |\n|---|---|---|\n"
       << "| coverage C (eq. 1) | " << coverage(atlas) << " | "
       << (kind == AtlasKind::Uniform ? "0.91" : "0.93") << " |\n"
       << "| relative scale S (eq. 2) | " << relativeScale(atlas) << " | "
       << (kind == AtlasKind::Uniform ? "1.75" : kind == AtlasKind::Area ? "0.66" : "0.86") << " |\n"
       << "| triangles | " << atlas.triangles.size() << " | |\n| legs (texels) | " << L.minLegs << " .. " << L.maxLegs
       << " | |\n| eq. 3 pair edge | " << atlas.eq3Edge << " | |\n"
       << "| mesh edges: open / non-manifold | " << L.openEdges << " / " << L.nonManifoldEdges << " | |\n\n"
       << "![atlas](atlas.png) ![textured, bilinear](render_bilinear.png) ![per-pixel](per_pixel.png) "
       << "![truth](truth.png) ![relative scale (Fig. 7)](scale.png)\n\n"
       << "| seams (screen pixels reading a background or foreign texel) | nearest | bilinear |\n|---|---|---|\n"
       << "| seam-free layout | " << v.nearest.seamPixels << " | " << v.bilinear.seamPixels << " |\n"
       << "| standard layout (Fig. 2) | " << v.stdNearest.seamPixels << " | " << v.stdBilinear.seamPixels << " |\n\n"
       << "| RMS vs " << a.truth << "x" << a.truth << " truth | value |\n|---|---|\n"
       << "| atlas, nearest | " << v.dN.rmsError << " |\n| atlas, bilinear | " << v.dB.rmsError << " |\n"
       << "| per-pixel render | " << v.dP.rmsError << " |\n";
    if (a.mip) {
        md << "| atlas, trilinear (MIP) | " << j["rms_vs_truth"]["atlas_trilinear"].get<double>() << " |\n\n"
           << "MIP texels averaging non-neighbours, level 0 up: " << j["mip"]["mixing_texels"].dump() << "\n";
    }
    if (j.contains("turntable"))
        md << "\nTurntable, " << a.turntable << " frames: flicker (temporal RMS vs the truth) atlas bilinear "
           << j["turntable"]["flicker"]["atlas_bilinear"].get<double>() << ", per-pixel "
           << j["turntable"]["flicker"]["per_pixel"].get<double>() << "; mean RMS vs truth atlas "
           << j["turntable"]["rms_vs_truth_mean"]["atlas_bilinear"].get<double>() << ", per-pixel "
           << j["turntable"]["rms_vs_truth_mean"]["per_pixel"].get<double>() << ".\n";
    if (j.contains("hardware") && j["hardware"].contains("cycles"))
        md << "\nFill through " << prof->name << " RTL: " << fill.texels << " texels, " << fill.cycles << " cycles, "
           << fill.mismatches << " mismatches" << (j["hardware"]["fill_ms_at_fmax"].is_null() ? std::string()
               : ", " + j["hardware"]["fill_ms_at_fmax"].dump() + " ms at " + j["hardware"]["fmax_mhz"].dump() + " MHz")
           << (j["hardware"].contains("fill_ms_at_layout_fmax")
               ? ", " + j["hardware"]["fill_ms_at_layout_fmax"].dump() + " ms at " + j["hardware"]["fmax_layout_mhz"].dump() +
                     " MHz after layout" : std::string())
           << ".\n";
    if (j.contains("hardware") && j["hardware"].contains("paper_table3_host_hz") && j["hardware"].contains("fill_hz_at_fmax"))
        md << "Fill rate " << j["hardware"]["fill_hz_at_fmax"].get<double>() << " Hz; the paper's host (Table 3) at "
           << atlas.size() << "^2: " << j["hardware"]["paper_table3_host_hz"]["octaves_1"].get<double>() << " Hz (1 octave), "
           << j["hardware"]["paper_table3_host_hz"]["octaves_4"].get<double>() << " Hz (4 octaves).\n";
    if (j.contains("gpu")) {
        const auto& g = j["gpu"];
        md << "\n![atlas filled on the GPU](atlas_gpu.png) ![textured from it, bilinear](render_gpu_bilinear.png)\n\n"
           << "Fill on the GPU (Hart 2001 multipass, variant " << g["variant"].get<std::string>() << ", "
           << g["interp"].get<std::string>() << ", b_f " << g["b_f"].get<int>() << ", "
           << g["renderer"].get<std::string>() << "): " << g["texels"].get<long long>() << " texels, "
           << g["octaves"].get<int>() << " octave runs of " << g["draws_per_octave"].get<int>() << " draws ("
           << g["draws"].get<int>() << " in all), " << g["texels_per_second"].get<double>() << " texels/s ("
           << g["texels_per_second_passes"].get<double>() << " in the passes alone; the host reference "
           << j["fill"]["texels_per_second"].get<double>() << "); " << g["cpu_model"]["mismatches"].get<long long>()
           << " of " << g["cpu_model"]["noise_values"].get<long long>() << " noise values differ from the CPU model.\n\n"
           << "| RMS, render from the GPU atlas (bilinear) | value |\n|---|---|\n"
           << "| vs " << a.truth << "x" << a.truth << " truth | " << g["render_bilinear_rms_vs_truth"].get<double>() << " |\n"
           << "| vs the per-pixel render | " << g["render_bilinear_rms_vs_per_pixel"].get<double>() << " |\n"
           << "| GPU atlas vs host atlas (texels) | " << g["vs_reference"]["rms"].get<double>() << " |\n";
    }
    return md.str();
}

}  // namespace pst::cli
