// GL helpers shared by the multipass runner (gl_multipass.cpp) and the single-pass shader
// (single_pass.cpp): errors as exceptions, shader programs, textures of a target format,
// upload and readback of luminance images, timing.
#pragma once

#include <GLES3/gl3.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "gl_multipass.h"

namespace pst::gpu::detail {

void check(const char* what);                        // throws "GL: what: error 0x...." on a GL error
GLuint compile(GLenum type, const char* text);
GLuint link(const char* fragment);                   // the full-screen vertex shader + FRAGMENT
GLenum internalFormat(TargetFormat f);
GLuint makeTexture(int w, int h, TargetFormat f = TargetFormat::RGBA8);
void upload(GLuint tex, int w, int h, const uint32_t* lum, TargetFormat f = TargetFormat::RGBA8);
std::vector<uint32_t> readback(int w, int h, TargetFormat f);
double msSince(std::chrono::steady_clock::time_point t0);
// The timed frames: `frames` (at least 1) runs of drawFrame, each ended by glFinish, into tm
// (frames, the mean msPerFrame and the fastest msPerFrameMin).
void timeFrames(Timing& tm, int frames, const std::function<void()>& drawFrame);

}  // namespace pst::gpu::detail
