// pst atlas, its steps: the scene's layer-0 triangles in a meshed atlas (Carr and Hart
// section 4), filled through the reference (and a profile's golden model and RTL, scoreboarded),
// the view drawn by texture mapping the atlas, compared with the per-pixel render and the ground
// truth. atlas.cpp: the options and the steps in order; atlas_report.cpp: atlas.json, atlas.md
// and the turntable.
#pragma once

#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "atlas.h"
#include "atlas_fill.h"
#include "atlas_render.h"
#include "common.h"
#include "imageio.h"
#include "multires.h"

namespace pst::cli {

struct AtlasArgs {
    std::string scene, outDir, kind = "uniform", magnification = "bilinear";
    int size = 512, image = 0, truth = 4, threads = 0;
    bool quiet = false, mip = false;
    int turntable = 0;   // frames of a turn of the camera about the target (0 = none)
    std::string filler = "host";  // host (the reference) | gpu (also the multipass GPU noise)
    GpuFillOptions gpu;           // --variant, --bf: --filler gpu only
};

// Step 1: the atlas and the standard (not seam-free) layout of the same triangles.
struct AtlasLayout {
    AtlasOptions options;
    Atlas atlas, standard;
    long long openEdges = 0, nonManifoldEdges = 0;
    int minLegs = 0, maxLegs = 0;
    std::vector<int> owners, stdOwners;
};

// Step 3: the view texture-mapped with the atlas, the standard layout's seams, the per-pixel
// render and the truth.
struct AtlasViews {
    AtlasRender nearest, bilinear, stdNearest, stdBilinear, hwBilinear, trilinear, gpuBilinear;
    RenderResult perPixel;
    ImageDiff dN, dB, dP, dBP;
    std::vector<long long> mixing;   // --mip: texels averaging non-neighbours per level
};

// Step 5: the turntable's figures and frames.
struct Turntable {
    double flA = 0, flP = 0, flM = 0, rmsA = 0, rmsP = 0, rmsM = 0;
    std::vector<std::pair<std::string, Image>> frames;
};

// atlas_report.cpp
nlohmann::json atlasJson(const AtlasArgs& a, const AtlasLayout& L, const AtlasViews& v, const AtlasFill& fill,
                         const Scene& scene, std::ostringstream& line);
// The hardware fill's figures (j["hardware"]); returns 1 when the RTL fill failed.
int hardwareJson(const HwArgs& hw, const Profile& prof, const AtlasLayout& L, const AtlasViews& v,
                 const AtlasFill& fill, nlohmann::json& j, std::ostringstream& line);
// The GPU fill's figures (j["gpu"]); returns 1 when a GPU value differs from the CPU model's.
int gpuJson(const GpuFill& gpu, const AtlasViews& v, const AtlasFill& fill, nlohmann::json& j, std::ostringstream& line);
Turntable runTurntable(const AtlasArgs& a, const Scene& scene, const AtlasLayout& L, const AtlasFill& fill,
                       const std::function<void(const std::string&)>& say);
void turntableJson(const AtlasArgs& a, const Turntable& t, nlohmann::json& j, std::ostringstream& line);
std::string atlasMarkdown(const AtlasArgs& a, const AtlasLayout& L, const AtlasViews& v, const AtlasFill& fill,
                          const std::optional<Profile>& prof, const nlohmann::json& j);

}  // namespace pst::cli
