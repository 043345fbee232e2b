// GL helpers of the multipass runner and the single-pass shader; see gl_util.h.
#include "gl_util.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace pst::gpu::detail {
namespace {

// A full-screen triangle from gl_VertexID (no vertex buffer).
const char* kVertex = R"(#version 300 es
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

}  // namespace

void check(const char* what) {
    const GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "0x%04x", e);
        throw std::runtime_error(std::string("GL: ") + what + ": error " + buf);
    }
}

GLuint compile(GLenum type, const char* text) {
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 1, &text, nullptr);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(sh, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("GL: shader compile: ") + log);
    }
    return sh;
}

GLuint link(const char* fragment) {
    GLuint prog = glCreateProgram();
    GLuint vs = compile(GL_VERTEX_SHADER, kVertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    glLinkProgram(prog);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetProgramInfoLog(prog, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("GL: program link: ") + log);
    }
    return prog;
}

#ifndef GL_R16_EXT
#define GL_R16_EXT 0x822A
#endif

GLenum internalFormat(TargetFormat f) {
    return f == TargetFormat::RGB10A2 ? GL_RGB10_A2 : f == TargetFormat::R16 ? GL_R16_EXT : GL_RGBA8;
}

GLuint makeTexture(int w, int h, TargetFormat f) {
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, internalFormat(f), w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return tex;
}

// Luminance values -> texels of the format (R = G = B = v, A = 1; R16: R only).
void upload(GLuint tex, int w, int h, const uint32_t* lum, TargetFormat f) {
    const size_t n = size_t(w) * h;
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (f == TargetFormat::RGBA8) {
        std::vector<uint8_t> rgba(n * 4);
        for (size_t i = 0; i < n; ++i) {
            rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = uint8_t(lum[i]);
            rgba[4 * i + 3] = 255;
        }
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    } else if (f == TargetFormat::RGB10A2) {
        std::vector<uint32_t> px(n);
        for (size_t i = 0; i < n; ++i) px[i] = lum[i] | lum[i] << 10 | lum[i] << 20 | 3u << 30;
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, px.data());
    } else {
        std::vector<uint16_t> px(lum, lum + n);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RED, GL_UNSIGNED_SHORT, px.data());
    }
}

// The R channel of the bound framebuffer's w x h pixels as values of the format.
std::vector<uint32_t> readback(int w, int h, TargetFormat f) {
    const size_t n = size_t(w) * h;
    std::vector<uint32_t> out(n);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (f == TargetFormat::RGBA8) {
        std::vector<uint8_t> rgba(n * 4);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        for (size_t i = 0; i < n; ++i) out[i] = rgba[4 * i];
    } else if (f == TargetFormat::RGB10A2) {
        std::vector<uint32_t> px(n);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, px.data());
        for (size_t i = 0; i < n; ++i) out[i] = px[i] & 1023;
    } else {
        std::vector<uint16_t> px(n * 4);  // EXT_texture_norm16: RGBA / UNSIGNED_SHORT
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_SHORT, px.data());
        for (size_t i = 0; i < n; ++i) out[i] = px[4 * i];
    }
    return out;
}

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void timeFrames(Timing& tm, int frames, const std::function<void()>& drawFrame) {
    tm.frames = std::max(1, frames);
    double total = 0;
    tm.msPerFrameMin = 1e300;
    for (int f = 0; f < tm.frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        drawFrame();
        glFinish();
        const double ms = msSince(t0);
        total += ms;
        tm.msPerFrameMin = std::min(tm.msPerFrameMin, ms);
    }
    tm.msPerFrame = total / tm.frames;
}


}  // namespace pst::gpu::detail

namespace pst::gpu {

double loadAverage() {
    double l = -1;
    if (FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf", &l) != 1) l = -1;
        std::fclose(f);
    }
    return l;
}

}  // namespace pst::gpu
