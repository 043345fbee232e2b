// The single-pass fragment shader of the same noise (the upper bound of section 6's proposals),
// and gpuNoise, the multipass noise of a list of solid-texture coordinates (an atlas's texels);
// see gl_multipass.h.
#include "gl_multipass.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "gl_util.h"

namespace pst::gpu {

using namespace pst::multipass;
using namespace detail;

namespace {

// One draw: Rayshade's value noise with the 8-bit hash (Variant::Xor's noise) in float.
const char* kSinglePass = R"(#version 300 es
precision highp float;
precision highp int;
uniform highp sampler2D s;
uniform highp sampler2D t;
uniform highp sampler2D r;
uniform highp sampler2D perm;   // P (bytes / 255)
uniform highp sampler2D value;  // 0.5 R[P[m]] + 1/2 (bytes / 255)
uniform int bf;
uniform int scurve;
out vec4 color;
int P(int i) { return int(texelFetch(perm, ivec2(i & 255, 0), 0).r * 255.0 + 0.5); }
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    int c[3];
    c[0] = int(texelFetch(s, p, 0).r * 255.0 + 0.5);
    c[1] = int(texelFetch(t, p, 0).r * 255.0 + 0.5);
    c[2] = int(texelFetch(r, p, 0).r * 255.0 + 0.5);
    int K[3];
    float u[3];
    for (int a = 0; a < 3; ++a) {
        K[a] = (c[a] >> bf) + 64;  // Rayshade's lattice index + 1e6, low 8 bits
        u[a] = float(c[a] & ((1 << bf) - 1)) / float(1 << bf);
        if (scurve != 0) u[a] = u[a] * u[a] * (3.0 - 2.0 * u[a]);
    }
    float n = 0.0;
    for (int k = 0; k < 8; ++k) {
        int bx = k & 1, by = (k >> 1) & 1, bz = (k >> 2) & 1;
        int x = P(P(K[0] + bx) ^ ((K[1] + by) & 255)) ^ ((K[2] + bz) & 255);
        float v = texelFetch(value, ivec2(x, 0), 0).r;
        n += v * (bx == 1 ? u[0] : 1.0 - u[0]) * (by == 1 ? u[1] : 1.0 - u[1]) * (bz == 1 ? u[2] : 1.0 - u[2]);
    }
    color = vec4(n, n, n, 1.0);
}
)";

}  // namespace

Image8 singlePassNoise(const Image8& s, const Image8& t, const Image8& r, const Params& params, int frames,
                       Timing* timing) {
    const int w = s.width, h = s.height;
    const GLuint prog = link(kSinglePass);
    GLuint tex[5], fbo, vao, target = makeTexture(w, h);
    for (int i = 0; i < 3; ++i) tex[i] = makeTexture(w, h);
    tex[3] = makeTexture(256, 1);
    tex[4] = makeTexture(256, 1);
    const Tables tables = makeTables(params);
    Timing tm;
    glFinish();
    auto t0 = std::chrono::steady_clock::now();
    upload(tex[0], w, h, s.px.data());
    upload(tex[1], w, h, t.px.data());
    upload(tex[2], w, h, r.px.data());
    upload(tex[3], 256, 1, tables[Perm].data());
    upload(tex[4], 256, 1, tables[ValuePerm].data());
    glFinish();
    tm.msUpload = msSince(t0);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glViewport(0, 0, w, h);
    glDisable(GL_DITHER);
    glDisable(GL_BLEND);
    glUseProgram(prog);
    const char* names[5] = {"s", "t", "r", "perm", "value"};
    for (int i = 0; i < 5; ++i) {
        glUniform1i(glGetUniformLocation(prog, names[i]), i);
        glActiveTexture(GL_TEXTURE0 + i);
        glBindTexture(GL_TEXTURE_2D, tex[i]);
    }
    glUniform1i(glGetUniformLocation(prog, "bf"), params.format.bf);
    glUniform1i(glGetUniformLocation(prog, "scurve"), params.interp == Interp::Scurve);
    tm.draws = 1;
    timeFrames(tm, frames, [] { glDrawArrays(GL_TRIANGLES, 0, 3); });
    check("single pass");
    Image8 out{w, h, readback(w, h, TargetFormat::RGBA8)};
    glDeleteTextures(5, tex);
    glDeleteTextures(1, &target);
    glDeleteFramebuffers(1, &fbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
    check("single pass readback");
    if (timing) *timing = tm;
    return out;
}

std::vector<float> gpuNoise(const std::vector<glm::dvec3>& coords, const Params& params,
                            BlendArith arith, Timing* timing) {
    if (coords.empty()) return {};
    EglContext ctx;
    // Lay the coordinates out as rows of up to 1024 pixels; the padding is coordinate 0.
    const int w = int(std::min<size_t>(coords.size(), 1024));
    const int h = int((coords.size() + w - 1) / w);
    Image8 s{w, h, std::vector<uint32_t>(size_t(w) * h, 0)}, t = s, r = s;
    for (size_t i = 0; i < coords.size(); ++i) {
        s.px[i] = toFixed(coords[i].x, params.format);
        t.px[i] = toFixed(coords[i].y, params.format);
        r.px[i] = toFixed(coords[i].z, params.format);
    }
    GlMultipass gl(w, h);
    const Image8 n = gl.run(makeProgram(params), makeTables(params), s, t, r, arith, 1, timing);
    std::vector<float> out(coords.size());
    for (size_t i = 0; i < coords.size(); ++i) out[i] = n.px[i] / 255.0f;
    return out;
}

}  // namespace pst::gpu

