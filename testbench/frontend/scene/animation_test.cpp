// The time track of scene files: interpolation, the fields it reaches, and its errors.
#include <cmath>

#include <gtest/gtest.h>

#include "scene.h"

namespace pst {
namespace {

const std::string kStill = R"(
[image]
width = 8
height = 8
[camera]
eye = [0.0, 0.0, 5.0]
fovy = 40.0
[textures.t]
colormap = { ramp = [[0.0, 0, 0, 0], [1.0, 1, 1, 1]] }
[[textures.t.octaves]]
amplitude = 0.5
offset = [1.0, 2.0, 3.0]
[[textures.t.octaves]]
amplitude = 0.25
[[objects]]
mesh = "cube"
texture = "t"
)";

std::string withTrack(const std::string& track) { return kStill + "[animation]\nframes = 3\n" + track; }

void expectError(const std::string& text, std::initializer_list<const char*> parts) {
    try {
        parseScene(text, "anim.toml");
        FAIL() << "no error for:\n" << text;
    } catch (const InputError& e) {
        for (const char* p : parts)
            EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << "message '" << e.what() << "' lacks '" << p << "'";
    }
}

TEST(Animation, StillHasNoTrack) {
    Scene s = parseScene(kStill, "still.toml");
    EXPECT_TRUE(s.animation.empty());
    Scene a = parseSceneAt(kStill, "still.toml", 0.7);
    EXPECT_EQ(a.camera.eye, s.camera.eye);
}

TEST(Animation, CameraKeysInterpolateLinearlyAndHoldAtTheEnds) {
    const std::string text = withTrack(R"(
[[animation.track]]
field = "camera.eye"
keys = [[0.25, 0.0, 0.0, 4.0], [0.75, 0.0, 2.0, 6.0]]
)");
    Scene s = parseScene(text, "a.toml");
    ASSERT_EQ(s.animation.tracks.size(), 1u);
    EXPECT_EQ(s.animation.frames, 3);
    EXPECT_EQ(s.camera.eye, glm::dvec3(0, 0, 5));  // the still keeps the file's value
    EXPECT_EQ(parseSceneAt(text, "a.toml", 0.0).camera.eye, glm::dvec3(0, 0, 4));
    EXPECT_EQ(parseSceneAt(text, "a.toml", 0.5).camera.eye, glm::dvec3(0, 1, 5));
    EXPECT_EQ(parseSceneAt(text, "a.toml", 1.0).camera.eye, glm::dvec3(0, 2, 6));
}

TEST(Animation, WildcardReachesEveryOctaveAndMissingFieldsAreAdded) {
    const std::string text = withTrack(R"(
[[animation.track]]
field = "textures.t.octaves[*].offset"
keys = [[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 2.0]]
[[animation.track]]
field = "textures.t.octaves[1].amplitude"
keys = [[0.0, 0.0], [1.0, 1.0]]
[[animation.track]]
field = "objects[0].tex_rotate"
keys = [[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 90.0, 0.0]]
)");
    Scene s = parseSceneAt(text, "a.toml", 0.5);
    EXPECT_EQ(s.textures[0].octaves[0].offset, glm::dvec3(0, 0, 1));
    EXPECT_EQ(s.textures[0].octaves[1].offset, glm::dvec3(0, 0, 1));
    EXPECT_EQ(s.textures[0].octaves[0].amplitude, 0.5);
    EXPECT_EQ(s.textures[0].octaves[1].amplitude, 0.5);
    // The cube's texture space turns with tex_rotate (45 degrees at t = 0.5).
    Scene s0 = parseSceneAt(text, "a.toml", 0.0);
    EXPECT_NE(s.objects[0].mesh.texcoords[0], s0.objects[0].mesh.texcoords[0]);
}

TEST(Animation, ErrorsNameFileLineAndField) {
    expectError(withTrack("[[animation.track]]\nfield = \"camera.eye\"\nkeys = [[0.0, 1.0, 2.0]]\n"),
                {"anim.toml:", "animation.track[0].keys[0]", "takes 3 number(s), got 2"});
    expectError(withTrack("[[animation.track]]\nfield = \"camera.eyes\"\nkeys = [[0.0, 1.0]]\n"),
                {"anim.toml:", "animation.track[0].keys[0]", "camera.eyes: unknown key"});
    expectError(withTrack("[[animation.track]]\nfield = \"image.width\"\nkeys = [[0.0, 1.0]]\n"),
                {"animation.track[0].field", "only camera, textures and objects"});
    expectError(withTrack("[[animation.track]]\nfield = \"textures.u.quadric\"\nkeys = [[0.0, 1.0]]\n"),
                {"animation.track[0].field", "'u' is not in the file"});
    expectError(withTrack("[[animation.track]]\nfield = \"objects[3].rotate\"\nkeys = [[0.0, 1.0, 1.0, 1.0]]\n"),
                {"animation.track[0].field", "has 1 entries"});
    expectError(withTrack("[[animation.track]]\nfield = \"camera..eye\"\nkeys = [[0.0, 1.0]]\n"),
                {"animation.track[0].field", "not a field path"});
    expectError(withTrack("[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [[1.5, 30.0]]\n"),
                {"anim.toml:", "animation.track[0].keys[0]", "time must be in [0, 1]"});
    expectError(withTrack("[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [[0.5, 30.0], [0.2, 30.0]]\n"),
                {"animation.track[0].keys[1]", "must not decrease"});
    expectError(withTrack("[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [[0.0, nan]]\n"),
                {"animation.track[0].keys[0][1]", "NaN"});
    expectError(withTrack("[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [[0.0, inf]]\n"),
                {"animation.track[0].keys[0][1]", "infinite"});
    // A key that makes the scene invalid names the key's line and the scene's own complaint.
    expectError(withTrack("[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [\n [0.0, 30.0],\n [1.0, 200.0]]\n"),
                {"anim.toml:24: animation.track[0].keys[1]: camera.fovy: must be in (0, 180)"});
    expectError(withTrack("[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [[0.0, 30.0]]\nspeed = 2\n"),
                {"animation.track[0].speed", "unknown key"});
    expectError(withTrack(""), {"animation.track", "missing"});
    expectError(kStill + "[animation]\nframes = 100000\n[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [[0.0, 30.0]]\n",
                {"anim.toml:", "animation.frames", "must be in [1, 10000]"});
    expectError(kStill + "[animation]\nfps = 0\n[[animation.track]]\nfield = \"camera.fovy\"\nkeys = [[0.0, 30.0]]\n",
                {"animation.fps", "must be in (0, 240]"});
}

TEST(Animation, InvalidBetweenKeysFailsAtThatTime) {
    // eye passes through target halfway: valid at both keys, not at t = 0.5.
    const std::string text = withTrack(R"(
[[animation.track]]
field = "camera.eye"
keys = [[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, -1.0]]
)");
    EXPECT_NO_THROW(parseScene(text, "a.toml"));
    EXPECT_NO_THROW(parseSceneAt(text, "a.toml", 0.25));
    try {
        parseSceneAt(text, "a.toml", 0.5);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("a.toml: animation at t = 0.5: camera.target: must differ"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace pst
