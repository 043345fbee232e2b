// End-to-end rendering through the reference model: determinism, the filter against the
// supersampled ground truth, and layer compositing.
#include "render.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include <gtest/gtest.h>

#include "imageio.h"
#include "source_dir.h"

namespace pst {
namespace {
namespace fs = std::filesystem;

std::string scenePath(const char* name) { return sourceDir() + "/scenes/" + name + ".toml"; }

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

TEST(Render, TwiceGivesIdenticalBytes) {
    const fs::path dir = fs::temp_directory_path() / ("pst_render_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const char* name : {"wood_teapot", "planet"}) {
        SCOPED_TRACE(name);
        Scene scene = loadScene(scenePath(name), 64, 64);
        RenderOptions one, two;
        one.threads = 1;
        two.threads = 2;
        RenderResult a = render(scene, one), b = render(scene, two);
        writeImage(a.filtered, (dir / "a.png").string());
        writeImage(b.filtered, (dir / "b.png").string());
        const std::string pa = slurp(dir / "a.png"), pb = slurp(dir / "b.png");
        EXPECT_GT(pa.size(), 100u);
        EXPECT_EQ(pa, pb);
        EXPECT_EQ(a.filterWidth.data, b.filterWidth.data);
        EXPECT_GT(a.stats.fragments, 64 * 64 / 10);
    }
    fs::remove_all(dir);
}

TEST(Render, FilteredZonePlateIsCloserToTruth) {
    Scene scene = loadScene(scenePath("zoneplate"));
    RenderOptions opt;
    opt.truthSamples = 4;
    RenderResult r = render(scene, opt);
    const ImageDiff f = compareRgb(r.filtered, r.truth), u = compareRgb(r.unfiltered, r.truth);
    std::printf("zone plate 256x256, truth 4x4: RMS vs truth filtered %.4f, unfiltered %.4f\n",
                f.rmsError, u.rmsError);
    EXPECT_LT(f.rmsError, u.rmsError);
    // The whole image is covered by the zone-plate square.
    EXPECT_EQ(r.stats.fragments, 256 * 256);
}

TEST(Render, ZonePlateJacobianIsOnePixelOfTheUnitSquare) {
    Scene scene = loadScene(scenePath("zoneplate"));
    auto frags = sceneFragments(scene, 0);
    ASSERT_EQ(frags.size(), 256u * 256u);
    // Paper section 3.4: ds/dx = dt/dy = 1/256 over the unit square.
    const Fragment& f = frags[128 * 256 + 37];
    EXPECT_NEAR(std::abs(f.dsdx.x) + std::abs(f.dsdx.y) + std::abs(f.dsdx.z), 1.0 / 256, 1e-9);
    EXPECT_NEAR(std::abs(f.dsdy.x) + std::abs(f.dsdy.y) + std::abs(f.dsdy.z), 1.0 / 256, 1e-9);
    EXPECT_NEAR(f.s.x, (37 + 0.5) / 256, 1e-9);
}

// A transparent "over" layer leaves the image as it was; an opaque one replaces it.
TEST(Render, LayersCompositeOver) {
    const std::string base = R"(
[image]
width = 16
height = 16
[camera]
eye = [0.0, 0.0, 3.0]
[textures.red]
colormap = { size = 1, ramp = [[0.0, 1.0, 0.0, 0.0, 1.0]] }
[textures.glass]
colormap = { size = 1, ramp = [[0.0, 0.0, 0.0, 1.0, ALPHA]] }
[[objects]]
mesh = "plane"
half_size = 5.0
rotate = [90.0, 0.0, 0.0]
texture = "red"
[[objects]]
mesh = "plane"
half_size = 5.0
rotate = [90.0, 0.0, 0.0]
translate = [0.0, 0.0, 0.5]
texture = "glass"
layer = 1
)";
    for (double alpha : {0.0, 0.25, 1.0}) {
        std::string text = base;
        text.replace(text.find("ALPHA"), 5, std::to_string(alpha));
        RenderResult r = render(parseScene(text, "layers.toml"));
        const float* p = r.filtered.pixel(8, 8);
        EXPECT_NEAR(p[0], 1.0 - alpha, 1e-6);
        EXPECT_NEAR(p[2], alpha, 1e-6);
        EXPECT_NEAR(p[3], 1.0, 1e-6);
    }
}

}  // namespace
}  // namespace pst
