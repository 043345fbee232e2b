// The multipass noise (Hart 2001, section 4; model/multipass/program.h) on OpenGL ES 3: every
// image an RGBA8 texture (the luminance in R = G = B), every pass one draw of a full-screen
// triangle whose fragment shader does exactly that pass's operation, the result stored by the
// GL's float -> UNORM8 conversion. The bit-accurate CPU model (model/multipass/cpu_model.h) is
// what it must equal, pixel for pixel.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cpu_model.h"
#include "egl_context.h"
#include "program.h"
#include "tables.h"

namespace pst::gpu {

// How a blend pass is carried out.
//   Shader: the pass's shader reads dst and src as textures and writes the blended value to a
//           fresh render target (render to texture, ping-pong): the result is the specified
//           float -> UNORM conversion of a float expression, equal to the CPU model on any
//           conforming driver (every value far from a rounding tie, cpu_model.h).
//   Blend:  the paper's way, fixed-function glBlendFunc/glBlendEquation into the target.
//           Add and subtract of UNORM8 are exact; for multiply the specification says only
//           "as if carried out in floating point ... precision no lower than the destination",
//           so a driver may differ from round(D S / 255) by an LSB per multiply.
enum class BlendArith { Shader, Blend };

// The images' texture format (section 6.1's precision): RGBA8 (b = 8, the paper's), RGB10_A2
// (b = 10), R16_EXT (b = 16, GL_EXT_texture_norm16). The program's Program::b must match.
enum class TargetFormat { RGBA8, RGB10A2, R16 };
int formatBits(TargetFormat f);
const char* formatName(TargetFormat f);

struct Timing {
    int draws = 0;           // draw calls per frame (the paper's passes)
    int frames = 0;          // frames timed
    double msPerFrame = 0;   // the passes only, glFinish to glFinish, mean over frames
    double msPerFrameMin = 0;  // the fastest frame (the machine's load shows in the mean)
    double msUpload = 0;     // the three coordinate images to textures (first frame)
    double msReadback = 0;   // the noise texture to the host (glReadPixels)
};

class GlMultipass {
  public:
    // Needs a current context (EglContext); width x height images.
    GlMultipass(int width, int height, TargetFormat format = TargetFormat::RGBA8);
    ~GlMultipass();
    GlMultipass(const GlMultipass&) = delete;
    GlMultipass& operator=(const GlMultipass&) = delete;

    // Section 6.2: savetex as the paper did it, glCopyTexSubImage2D. When on, every draw renders
    // into one framebuffer texture and is then copied into its destination image's texture
    // (shader blends only); when off (the default), render to texture: the draw's target
    // becomes the image (a rename).
    void setCopyTexSubImage(bool on);

    // Section 6.2 in isolation: the time of one glCopyTexSubImage2D of a whole image (fbTex to an
    // image texture) and of one PixelTransfer draw (scale and bias, no map), each the minimum over
    // `reps` repetitions of `count` operations between glFinish calls, divided by `count`.
    double copyMs(int count, int reps);
    double drawMs(int count, int reps);

    // Runs the program `frames` times on the same input (the result is the same every frame;
    // more frames for timing) and reads tex_noise back.
    multipass::Image8 run(const multipass::Program& prog, const multipass::Tables& tables,
                          const multipass::Image8& s, const multipass::Image8& t,
                          const multipass::Image8& r, BlendArith arith, int frames = 1,
                          Timing* timing = nullptr);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The upper bound of section 6's proposals: the same noise as Variant::Xor (Rayshade's value
// noise with the 8-bit hash, model/noise.h Perm256, corners Value; linear or SCURVE weights of
// u = F / 2^b_f) in one draw of one fragment shader, float arithmetic, the tables as textures,
// written to RGBA8. Needs a current context. Returns the bytes; timing as GlMultipass::run.
multipass::Image8 singlePassNoise(const multipass::Image8& s, const multipass::Image8& t, const multipass::Image8& r,
                                  const multipass::Params& params, int frames = 1, Timing* timing = nullptr);

// For an atlas of solid-texture coordinates (the `pst atlas` filler): the noise n in [0, 1]
// (the byte / 255) at each coordinate, quantized by multipass::toFixed, on the GPU. Opens its
// own EGL context (throws EglUnavailable without one).
// The machine's 1-minute load average (/proc/loadavg; -1 where unknown), recorded beside every
// timing: on a shared machine the times measure the load as much as the passes.
double loadAverage();

std::vector<float> gpuNoise(const std::vector<glm::dvec3>& coords, const multipass::Params& params,
                            BlendArith arith = BlendArith::Shader, Timing* timing = nullptr);

}  // namespace pst::gpu
