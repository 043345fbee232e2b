// Scene and texture files: every paper scene parses; bad input names file, line and field.
#include "scene.h"
#include "source_dir.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace pst {
namespace {

const char* kMinimal = R"(
[image]
width = 32
height = 16
[camera]
eye = [0.0, 0.0, 5.0]
[textures.t]
quadric = { A = 1.0 }
colormap = { size = 4, wrap = "clamp", ramp = [[0.0, 0, 0, 0], [1.0, 1, 1, 1]] }
[[textures.t.octaves]]
amplitude = 0.5
scale = [2.0, 3.0, 4.0]
offset = [1.0, 2.0, 3.0]
[[objects]]
mesh = "cube"
texture = "t"
)";

// Expects parseScene to fail with a message containing every fragment of `parts`.
void expectError(const std::string& text, std::initializer_list<const char*> parts) {
    try {
        parseScene(text, "bad.toml");
        FAIL() << "no error for:\n" << text;
    } catch (const InputError& e) {
        for (const char* p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
            << "message '" << e.what() << "' lacks '" << p << "'";
        // The check-only parse (the fuzz target's) refuses it with the same message.
        try {
            checkScene(text, "bad.toml");
            ADD_FAILURE() << "checkScene accepts:\n" << text;
        } catch (const InputError& c) {
            EXPECT_EQ(std::string(c.what()), std::string(e.what()));
        }
    }
}

TEST(Scene, MinimalParses) {
    Scene s = parseScene(kMinimal, "min.toml");
    EXPECT_EQ(s.camera.width, 32);
    EXPECT_EQ(s.camera.height, 16);
    ASSERT_EQ(s.textures.size(), 1u);
    const Texture& t = s.textures[0];
    EXPECT_EQ(t.quadric.A, 1.0);
    ASSERT_EQ(t.octaves.size(), 1u);
    EXPECT_EQ(t.octaves[0].M[1][1], 3.0);
    EXPECT_EQ(t.octaves[0].M[0][1], 0.0);
    EXPECT_EQ(t.octaves[0].offset, glm::dvec3(1.0, 2.0, 3.0));
    EXPECT_EQ(t.clut.size(), 4);
    EXPECT_EQ(t.clut.wrap(), WrapMode::Clamp);
    // Entry i samples the ramp at (i + 0.5) / N.
    EXPECT_DOUBLE_EQ(t.clut.entries()[0].r, 0.125);
    EXPECT_DOUBLE_EQ(t.clut.entries()[3].g, 0.875);
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].mesh.positions.size(), s.objects[0].mesh.texcoords.size());
}

TEST(Scene, SizeOverride) {
    Scene s = parseScene(kMinimal, "min.toml", 64, 48);
    EXPECT_EQ(s.camera.width, 64);
    EXPECT_EQ(s.camera.height, 48);
}

TEST(Scene, MatrixIsRowsAsWritten) {
    std::string text = kMinimal;
    text.replace(text.find("scale = [2.0, 3.0, 4.0]"), 23, "matrix = [[1, 2, 3], [4, 5, 6], [7, 8, 9]]");
    Scene s = parseScene(text, "m.toml");
    const glm::dmat3& M = s.textures[0].octaves[0].M;
    EXPECT_EQ(M[1][0], 2.0);  // row 0, column 1
    EXPECT_EQ(M[0][1], 4.0);  // row 1, column 0
}

TEST(Scene, EveryPaperSceneParses) {
    const char* names[] = {"wood_teapot", "marble", "seascape", "fire", "planet", "moonrise",
                           "zoneplate", "wood_torus", "bases"};
    for (const char* n : names) {
        SCOPED_TRACE(n);
        const std::string path = sourceDir() + "/scenes/" + n + ".toml";
        Scene s = loadScene(path);
        EXPECT_FALSE(s.objects.empty());
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        EXPECT_NO_THROW(checkScene(text.str(), path));
        EXPECT_FALSE(s.textures.empty());
    }
    EXPECT_EQ(loadScene(sourceDir() + "/scenes/zoneplate.toml").camera.width, 256);
}

// Render and atlas skip zero-area triangles (mesh.h: zeroArea); no scene of the repository has
// one, so the rule changed none of their images.
TEST(Scene, NoSceneHasZeroAreaTriangles) {
    int scenes = 0;
    size_t triangles = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(sourceDir() + "/scenes")) {
        if (e.path().extension() != ".toml") continue;
        SCOPED_TRACE(e.path().string());
        Scene s;
        try {
            s = loadScene(e.path().string());
        } catch (const InputError&) {
            continue;  // not a scene (a profile or texture block kept beside one)
        }
        ++scenes;
        for (const SceneObject& o : s.objects) {
            EXPECT_EQ(zeroAreaTriangles(o.mesh), 0u) << o.meshSource;
            triangles += o.mesh.triangles.size();
        }
    }
    EXPECT_GT(scenes, 9);
    EXPECT_GT(triangles, 10000u);
}

// `text` with its first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
}

TEST(Scene, ErrorsNameFileLineAndField) {
    std::string t = kMinimal;
    // Bad value: line of the offending key.
    expectError(replaced(t, "size = 4", "size = 6"), {"bad.toml:9:", "textures.t.colormap.size", "power of two"});
    expectError(replaced(t, "amplitude = 0.5", "amplitude = nan"), {"bad.toml:11:", "textures.t.octaves[0].amplitude", "NaN"});
    expectError(replaced(t, "amplitude = 0.5", "amplitude = inf"), {"bad.toml:11:", "amplitude", "infinite"});
    expectError(replaced(t, "mesh = \"cube\"", "mesh = \"dodecahedron\""), {"bad.toml:15:", "objects[0].mesh", "unknown mesh"});
    expectError(replaced(t, "texture = \"t\"", "texture = \"u\""), {"bad.toml:16:", "objects[0].texture", "no texture named 'u'"});
    expectError(replaced(t, "amplitude = 0.5", "amplitud = 0.5"), {"bad.toml:11:", "amplitud", "unknown key"});
    expectError(replaced(t, "eye = [0.0, 0.0, 5.0]", "eye = [0.0, 5.0]"), {"bad.toml:6:", "camera.eye", "expected 3 numbers"});
    // Syntax error from toml++, with the line.
    expectError("[image]\nwidth = = 3\n", {"bad.toml:2:"});
    expectError(std::string(kMinimal) + "\n[[objects]]\nmesh = \"cube\"\ntexture = \"t\"\nfilter = 3\n",
                {"bad.toml:21:", "objects[1].filter", "unknown key"});
}

// A scene file is reported whole: the camera's, a texture's and an object's errors, each on its
// own line with its file and line; an object using the failed texture is not reported for it.
TEST(Scene, ReportsEveryErrorNotOnlyTheFirst) {
    std::string bad = kMinimal;
    bad.replace(bad.find("eye = [0.0, 0.0, 5.0]"), 21, "eye = [0.0, 5.0]");
    bad.replace(bad.find("size = 4"), 8, "size = 6");
    bad.replace(bad.find("mesh = \"cube\""), 13, "mesh = \"dodecahedron\"");
    bad += "\n[[objects]]\nmesh = \"cube\"\ntexture = \"u\"\n";
    expectError(bad, {"bad.toml:6: camera.eye", "bad.toml:9: textures.t.colormap.size", "bad.toml:15: objects[0].mesh",
                      "objects[1].texture: no texture named 'u'"});
    try {
        parseScene(bad, "bad.toml");
    } catch (const InputError& e) {
        std::istringstream lines(e.what());
        int n = 0;
        for (std::string line; std::getline(lines, line); ++n) EXPECT_EQ(line.rfind("bad.toml:", 0), 0u) << line;
        EXPECT_EQ(n, 4) << e.what();
    }
}

// kMinimal with a noise table on line 9.
std::string withNoise(const std::string& noise) {
    std::string t = kMinimal;
    const std::string q = "quadric = { A = 1.0 }";
    return t.replace(t.find(q), q.size(), q + "\nnoise = " + noise);
}

TEST(Scene, NoiseBasis) {
    Scene s = parseScene(withNoise("{ basis = \"worley\", metric = \"manhattan\", coef = [-1.0, 1.0], cell = 0.5 }"),
                         "ok.toml");
    const NoiseOptions& n = s.textures[0].noise;
    EXPECT_EQ(n.basis, NoiseBasis::Worley);
    EXPECT_EQ(n.metric, WorleyMetric::Manhattan);
    EXPECT_EQ(n.coef, (std::array<double, 4>{-1.0, 1.0, 0.0, 0.0}));
    EXPECT_EQ(n.cell, 0.5);
    EXPECT_EQ(s.textures[0].basisSource, "ok.toml:9: textures.t.noise.basis");
    s = parseScene(withNoise("{ basis = \"perlin2002\" }"), "ok.toml");
    EXPECT_EQ(s.textures[0].noise.basis, NoiseBasis::Perlin2002);
    // Default: Rayshade, no source.
    s = parseScene(kMinimal, "ok.toml");
    EXPECT_EQ(s.textures[0].noise.basis, NoiseBasis::Rayshade);
    EXPECT_EQ(s.textures[0].basisSource, "");

    expectError(withNoise("{ basis = \"simplex\" }"),
                {"bad.toml:9:", "textures.t.noise.basis", "unknown value 'simplex'", "perlin2002"});
    expectError(withNoise("{ basis = 3 }"), {"bad.toml:9:", "textures.t.noise.basis", "expected a string"});
    expectError(withNoise("{ basis = \"perlin2002\", interp = \"linear\" }"),
                {"bad.toml:9:", "textures.t.noise.interp", "rayshade only"});
    expectError(withNoise("{ interp = \"quintic\" }"), {"bad.toml:9:", "textures.t.noise.interp", "perlin2002"});
    expectError(withNoise("{ hash = \"perlin256\" }"), {"bad.toml:9:", "textures.t.noise.hash", "perlin2002"});
    expectError(withNoise("{ coef = [1.0] }"), {"bad.toml:9:", "textures.t.noise.coef", "worley only"});
    expectError(withNoise("{ basis = \"worley\", metric = \"chebyshev\" }"),
                {"bad.toml:9:", "textures.t.noise.metric", "euclid or manhattan"});
    expectError(withNoise("{ basis = \"worley\", coef = [1, 2, 3, 4, 5] }"),
                {"bad.toml:9:", "textures.t.noise.coef", "expected 1 to 4 numbers"});
    expectError(withNoise("{ basis = \"worley\", coef = [1.0, nan] }"),
                {"bad.toml:9:", "textures.t.noise.coef[1]", "NaN"});
    expectError(withNoise("{ basis = \"worley\", coef = [0.0, 0.0] }"),
                {"bad.toml:9:", "textures.t.noise.coef", "constant"});
    expectError(withNoise("{ basis = \"worley\", cell = inf }"), {"bad.toml:9:", "textures.t.noise.cell", "infinite"});
    expectError(withNoise("{ basis = \"worley\", seed = 1 }"), {"bad.toml:9:", "textures.t.noise.seed", "subband only"});
}

TEST(Scene, SubbandBasis) {
    Scene s = parseScene(withNoise("{ basis = \"subband\", orientations = 4, tile_size = 512, seed = 7, "
                                   "param = \"sphere\", weights = \"least_squares\" }"),
                         "ok.toml");
    const NoiseOptions& n = s.textures[0].noise;
    EXPECT_EQ(n.basis, NoiseBasis::Subband);
    EXPECT_EQ(n.orientations, 4);
    EXPECT_EQ(n.tileSize, 512);
    EXPECT_EQ(n.seed, 7u);
    EXPECT_EQ(n.param, SubbandParam::Sphere);
    EXPECT_EQ(n.weights, SubbandWeights::LeastSquares);
    s = parseScene(withNoise("{ basis = \"subband\" }"), "ok.toml");
    EXPECT_EQ(s.textures[0].noise.orientations, 8);
    EXPECT_EQ(s.textures[0].noise.tileSize, 256);
    EXPECT_EQ(s.textures[0].noise.param, SubbandParam::XZ);
    expectError(withNoise("{ basis = \"subband\", orientations = 6 }"),
                {"bad.toml:9:", "textures.t.noise.orientations", "must be 4 or 8"});
    expectError(withNoise("{ basis = \"subband\", tile_size = 384 }"),
                {"bad.toml:9:", "textures.t.noise.tile_size", "power of two"});
    expectError(withNoise("{ basis = \"subband\", tile_size = 2048 }"),
                {"bad.toml:9:", "textures.t.noise.tile_size", "power of two in [256, 1024]"});
    expectError(withNoise("{ basis = \"subband\", sigma = 0.0 }"), {"bad.toml:9:", "textures.t.noise.sigma", "(0, 16]"});
    EXPECT_EQ(parseScene(withNoise("{ basis = \"subband\", sigma = 0.5 }"), "ok.toml").textures[0].noise.sigma, 0.5);
    expectError(withNoise("{ basis = \"subband\", weights = \"exact\" }"),
                {"bad.toml:9:", "textures.t.noise.weights", "heuristic or least_squares"});
    expectError(withNoise("{ basis = \"perlin2002\", param = \"xy\" }"),
                {"bad.toml:9:", "textures.t.noise.param", "subband only"});
    // Tiles: 1024 x 1024 with 8 orientations is (3 x 45 floats + 1 double) x 1 Mi pixels = 548 MiB
    // a set (40 tiles, 5 isotropic sums, value and two derivatives; the white noise): one seed
    // fits in the bound, a second does not.
    std::string three = kMinimal;
    for (int k = 1; k <= 2; ++k)
        three += "[textures.u" + std::to_string(k) + "]\nnoise = { basis = \"subband\", tile_size = 1024, seed = " +
                 std::to_string(k) + " }\ncolormap = { size = 4, ramp = [[0.0, 0, 0, 0], [1.0, 1, 1, 1]] }\n";
    expectError(three, {"bad.toml:", "textures.u2.noise", "would take 1096 MiB (at most 1024)"});
    std::string bad = withNoise("{ basis = \"worley\" }");
    bad.replace(bad.find("noise = "), 0, "bandlimit = \"anisotropic\"\n");
    expectError(bad, {"bad.toml:9:", "textures.t.bandlimit", "needs basis subband"});
}

TEST(Scene, Bandlimit) {
    std::string text = kMinimal;
    EXPECT_EQ(parseScene(text, "min.toml").textures[0].bandlimit, Bandlimit::Off);
    text.insert(text.find("colormap ="), "bandlimit = \"footprint\"\n");
    EXPECT_EQ(parseScene(text, "min.toml").textures[0].bandlimit, Bandlimit::Footprint);
    std::string bad = kMinimal;
    bad.insert(bad.find("colormap ="), "bandlimit = \"on\"\n");
    expectError(bad, {"bad.toml:9: textures.t.bandlimit: unknown value 'on' (expected off, footprint, isotropic or anisotropic)"});
}

TEST(Scene, WidthCap) {
    std::string text = kMinimal;
    EXPECT_FALSE(parseScene(text, "min.toml").textures[0].widthCap);
    text.insert(text.find("colormap ="), "width_cap = \"on\"\n");
    const Scene sc = parseScene(text, "min.toml");
    EXPECT_TRUE(sc.textures[0].widthCap);
    EXPECT_EQ(sc.textures[0].widthCapSource, "min.toml:9: textures.t.width_cap");
    std::string bad = kMinimal;
    bad.insert(bad.find("colormap ="), "width_cap = true\n");
    expectError(bad, {"bad.toml:9: textures.t.width_cap"});
    bad = kMinimal;
    bad.insert(bad.find("colormap ="), "width_cap = \"yes\"\n");
    expectError(bad, {"bad.toml:9: textures.t.width_cap: unknown value 'yes' (expected on or off)"});
}

TEST(Scene, TextureBlockFile) {
    const std::string text = R"(
quadric = { A = 50.0, E = 50.0 }
filter = "box"
norm = "l1"
noise = { interp = "linear", corner = "value", hash = "perm256" }
colormap = { size = 2, wrap = "mod", interp = "step", ramp = [[0.0, 0, 0, 0], [0.5, 1, 1, 1]] }
)";
    Texture t = parseTexture(text, "tex.toml");
    EXPECT_NO_THROW(checkTexture(text, "tex.toml"));
    EXPECT_THROW(checkTexture("filter = \"gauss\"\n", "tex.toml"), InputError);
    EXPECT_EQ(t.filter, FilterKind::Box);
    EXPECT_EQ(t.norm, GradNorm::L1);
    EXPECT_EQ(t.noise.interp, NoiseInterp::Linear);
    EXPECT_EQ(t.noise.corner, NoiseCorner::Value);
    EXPECT_EQ(t.noise.hash, NoiseHash::Perm256);
    EXPECT_EQ(t.clut.entries()[0], glm::dvec4(0, 0, 0, 1));
    EXPECT_EQ(t.clut.entries()[1], glm::dvec4(1, 1, 1, 1));
    try {
        parseTexture("filter = \"gauss\"\n", "tex.toml");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("tex.toml:1: filter: unknown value 'gauss'"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace pst
