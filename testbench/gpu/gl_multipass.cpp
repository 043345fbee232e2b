// The multipass noise on OpenGL ES 3; see gl_multipass.h.
#include "gl_multipass.h"

#include <GLES3/gl3.h>

#include "gl_util.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>
#include <string>

namespace pst::gpu {

using namespace pst::multipass;

namespace {


// Section 4.1's blendtex with PixelTransfer (scale, bias) and PixelMap: the map is a 256 x 1
// texture indexed by round(c 255), c the clamped scaled value (the GL's PixelMap index rule).
const char* kTransfer = R"(#version 300 es
precision highp float;
precision highp int;
uniform highp sampler2D src;
uniform highp sampler2D map;
uniform float scale;
uniform float bias;
uniform int useMap;
uniform float M;  // 2^b - 1
uniform int quantize;  // b != 8: round here and write the code k as (k + qOff) / qDen (Impl::quantize)
uniform float qOff;
uniform float qDen;
out vec4 color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float y = clamp(texelFetch(src, p, 0).r * scale + bias, 0.0, 1.0);
    if (useMap != 0) {
        int i = int(floor(y * M + 0.5));  // the map: 256 entries per row
        y = texelFetch(map, ivec2(i & 255, i >> 8), 0).r;
    }
    if (quantize != 0) y = (floor(y * M + 0.5) + qOff) / qDen;
    color = vec4(y, y, y, 1.0);
}
)";

// A blend as a shader (BlendArith::Shader): dst and src read as textures.
const char* kBlend = R"(#version 300 es
precision highp float;
precision highp int;
uniform highp sampler2D dst;
uniform highp sampler2D src;
uniform int op;  // 0 add, 1 subtract (src - dst), 2 multiply, 3 multiply by 1 - src, 4 xor
uniform float M;  // 2^b - 1
uniform int quantize;
uniform float qOff;
uniform float qDen;
out vec4 color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float d = texelFetch(dst, p, 0).r, s = texelFetch(src, p, 0).r, y;
    if (op == 0) y = d + s;
    else if (op == 1) y = s - d;
    else if (op >= 2 && op <= 3 && quantize != 0) {
        // b > 8: round(D S / M) in integers (D S < 2^32 up to b = 16); float32 cannot resolve
        // how close D S / M comes to a half at b = 16 (a multiple of 1/M LSB)
        uint D = uint(d * M + 0.5), S = uint(s * M + 0.5), m = uint(M);
        if (op == 3) S = m - S;
        uint p = D * S, q = p / m;
        y = float(q + (2u * (p - q * m) >= m ? 1u : 0u)) / M;
    }
    else if (op == 2) y = d * s;
    else if (op == 3) y = d * (1.0 - s);
    else y = float(uint(d * M + 0.5) ^ uint(s * M + 0.5)) / M;  // 6.3: exclusive or
    y = clamp(y, 0.0, 1.0);
    if (quantize != 0) y = (floor(y * M + 0.5) + qOff) / qDen;
    color = vec4(y, y, y, 1.0);
}
)";

// One register-combiner pass (section 5; model/multipass/cpu_model.h namespace rc): the two
// general combiner stages and the final combiner in the 9-bit signed integer arithmetic the
// CPU model assumes, tex0 = src, tex1 = dst; the byte is written as byte / 255, which the
// float -> UNORM8 conversion stores exactly.
const char* kCombiner = R"(#version 300 es
precision highp float;
precision highp int;
uniform highp sampler2D tex0;
uniform highp sampler2D tex1;
uniform int op;  // 0 shift left (5.2), 1 +1 corner with wrap, 2 blend by the high bit (5.3)
uniform int k0;
uniform int k1;
uniform int alpha;
out vec4 color;
int clamp9(int k) { return clamp(k, -255, 255); }
int mul(int a, int b) {
    int p = a * b;
    int q = (abs(p) * 2 + 255) / 510;
    return clamp9(p < 0 ? -q : q);
}
const int kHalf = 128;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    int c = int(texelFetch(tex0, p, 0).r * 255.0 + 0.5);
    int out8;
    if (op == 0) {
        int spareA = mul(c, 255), spareRgb = clamp9(mul(c, 255) - kHalf);
        out8 = clamp9(2 * (spareA < kHalf ? mul(c, 255) : mul(spareRgb, 255)));
    } else if (op == 1) {
        int sum = clamp9(mul(c, 255) + mul(k0, 255));
        int a = clamp9(4 * (mul(c, 255) - mul(k1, 255)));
        out8 = a < kHalf ? mul(sum, 255) : mul(0, 0);
    } else {
        int acc = int(texelFetch(tex1, p, 0).r * 255.0 + 0.5);
        int spareA = mul(c, 255), col = spareA < kHalf ? mul(k0, 255) : mul(k1, 255);
        out8 = mul(alpha, col) + mul(255 - alpha, acc);
    }
    float y = float(clamp(out8, 0, 255)) / 255.0;
    color = vec4(y, y, y, 1.0);
}
)";


}  // namespace

using namespace detail;

int formatBits(TargetFormat f) { return f == TargetFormat::RGB10A2 ? 10 : f == TargetFormat::R16 ? 16 : 8; }
const char* formatName(TargetFormat f) {
    return f == TargetFormat::RGB10A2 ? "RGB10_A2" : f == TargetFormat::R16 ? "R16_EXT" : "RGBA8";
}

struct GlMultipass::Impl {
    int w, h;
    TargetFormat fmt = TargetFormat::RGBA8;
    float M = 255.f;
    // The specification stores a float y as "one of the two closest" UNORM values to y M,
    // rounding to nearest preferred. llvmpipe rounds on RGBA8 and R16 but stores floor(1024 y)
    // on RGB10_A2 (measured: y = 0.98 LSB stores 0; y = 772.25 LSB stores 773), which is
    // always one of the two closest to 1023 y, so conforming. For b != 8 the shaders
    // therefore round themselves and write the code k as a value both rules store as k:
    // (k + 1/2) / 1024 on RGB10_A2 (round(1023 y) = floor(1024 y) = k), (k + 1/4) / M on
    // R16. (RGBA8 keeps the paper's way: the framebuffer's conversion rounds.)
    bool quantize = false;
    float qOff = 0.f, qDen = 1.f;
    GLuint fbo = 0, vao = 0;
    GLuint transfer = 0, blend = 0, combiner = 0;
    GLint tScale, tBias, tUseMap, bOp, cOp, cK0, cK1, cAlpha;
    std::array<GLuint, kImageCount> img{};  // the texture holding each image now
    GLuint scratch = 0;                     // the next render target of a ping-pong pass
    std::array<GLuint, kTableCount> table{};

    bool copy = false;  // section 6.2: every draw into fbTex, then glCopyTexSubImage2D
    GLuint fbTex = 0;

    void target(GLuint tex) {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    }
    // A pass's draw goes to scratch (render to texture) or to the framebuffer texture (copy).
    void begin() { target(copy ? fbTex : scratch); }
    void end(int dst) {
        if (!copy) {
            std::swap(scratch, img[dst]);
            return;
        }
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, img[dst]);
        glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, w, h);
    }
    void bind(int unit, GLuint tex) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, tex);
    }
    void draw() { glDrawArrays(GL_TRIANGLES, 0, 3); }

    // PixelTransfer into scratch, which then becomes dst (dst may be src: in-place CopyPixels).
    void runTransfer(const Pass& p) {
        begin();
        glUseProgram(transfer);
        glUniform1f(tScale, float(p.scale));
        glUniform1f(tBias, float(p.bias));
        glUniform1i(tUseMap, p.table != NoTable);
        bind(0, img[p.src]);
        bind(1, table[p.table != NoTable ? p.table : 0]);
        draw();
        end(p.dst);
    }

    // A register-combiner pass into scratch, which then becomes dst (dst may be src).
    void runCombiner(const Pass& p) {
        begin();
        glUseProgram(combiner);
        glUniform1i(cOp, p.op == Op::RcShiftLeft ? 0 : p.op == Op::RcIncWrap ? 1 : 2);
        glUniform1i(cK0, p.k0);
        glUniform1i(cK1, p.k1);
        glUniform1i(cAlpha, p.alpha);
        bind(0, img[p.src]);
        bind(1, img[p.dst]);
        draw();
        end(p.dst);
    }

    void runBlend(const Pass& p, BlendArith arith) {
        int op = p.op == Op::BlendAdd ? 0 : p.op == Op::BlendSub ? 1 : p.op == Op::BlendMul ? 2
                 : p.op == Op::BlendMulInv ? 3 : 4;
        // GLES has no glLogicOp: the exclusive or is always a shader (GLSL integers).
        if (arith == BlendArith::Shader || op == 4) {
            begin();
            glUseProgram(blend);
            glUniform1i(bOp, op);
            bind(0, img[p.dst]);
            bind(1, img[p.src]);
            draw();
            end(p.dst);
            return;
        }
        if (copy) throw std::logic_error("multipass: glCopyTexSubImage2D mode needs shader blends");
        if (p.src == p.dst) throw std::logic_error("multipass: a blend cannot read its own target");
        // The paper's way: blendtex(src) with BlendEquation/BlendFunc into the target.
        target(img[p.dst]);
        glUseProgram(transfer);
        glUniform1f(tScale, 1.0f);
        glUniform1f(tBias, 0.0f);
        glUniform1i(tUseMap, 0);
        bind(0, img[p.src]);
        bind(1, table[0]);
        glEnable(GL_BLEND);
        glBlendEquation(op == 1 ? GL_FUNC_SUBTRACT : GL_FUNC_ADD);
        if (op <= 1) glBlendFunc(GL_ONE, GL_ONE);
        else glBlendFunc(GL_ZERO, op == 2 ? GL_SRC_COLOR : GL_ONE_MINUS_SRC_COLOR);
        draw();
        glDisable(GL_BLEND);
    }
};

GlMultipass::GlMultipass(int width, int height, TargetFormat format) : impl_(new Impl) {
    Impl& m = *impl_;
    if (width < 1 || height < 1) throw std::invalid_argument("multipass: empty image");
    m.w = width;
    m.h = height;
    m.fmt = format;
    m.M = float((1 << formatBits(format)) - 1);
    m.quantize = format != TargetFormat::RGBA8;
    m.qOff = format == TargetFormat::RGB10A2 ? 0.5f : 0.25f;
    m.qDen = format == TargetFormat::RGB10A2 ? m.M + 1.f : m.M;
    m.transfer = link(kTransfer);
    m.blend = link(kBlend);
    glUseProgram(m.transfer);
    glUniform1i(glGetUniformLocation(m.transfer, "src"), 0);
    glUniform1i(glGetUniformLocation(m.transfer, "map"), 1);
    m.tScale = glGetUniformLocation(m.transfer, "scale");
    m.tBias = glGetUniformLocation(m.transfer, "bias");
    m.tUseMap = glGetUniformLocation(m.transfer, "useMap");
    glUniform1f(glGetUniformLocation(m.transfer, "M"), m.M);
    glUniform1i(glGetUniformLocation(m.transfer, "quantize"), m.quantize);
    glUniform1f(glGetUniformLocation(m.transfer, "qOff"), m.qOff);
    glUniform1f(glGetUniformLocation(m.transfer, "qDen"), m.qDen);
    glUseProgram(m.blend);
    glUniform1i(glGetUniformLocation(m.blend, "dst"), 0);
    glUniform1i(glGetUniformLocation(m.blend, "src"), 1);
    m.bOp = glGetUniformLocation(m.blend, "op");
    glUniform1f(glGetUniformLocation(m.blend, "M"), m.M);
    glUniform1i(glGetUniformLocation(m.blend, "quantize"), m.quantize);
    glUniform1f(glGetUniformLocation(m.blend, "qOff"), m.qOff);
    glUniform1f(glGetUniformLocation(m.blend, "qDen"), m.qDen);
    m.combiner = link(kCombiner);
    glUseProgram(m.combiner);
    glUniform1i(glGetUniformLocation(m.combiner, "tex0"), 0);
    glUniform1i(glGetUniformLocation(m.combiner, "tex1"), 1);
    m.cOp = glGetUniformLocation(m.combiner, "op");
    m.cK0 = glGetUniformLocation(m.combiner, "k0");
    m.cK1 = glGetUniformLocation(m.combiner, "k1");
    m.cAlpha = glGetUniformLocation(m.combiner, "alpha");
    for (GLuint& t : m.img) t = makeTexture(width, height, format);
    m.scratch = makeTexture(width, height, format);
    m.fbTex = makeTexture(width, height, format);
    for (GLuint& t : m.table) t = makeTexture(256, (int(m.M) + 1) / 256, format);
    glGenFramebuffers(1, &m.fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
    glGenVertexArrays(1, &m.vao);
    glBindVertexArray(m.vao);
    m.target(m.scratch);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error(std::string("GL: a ") + formatName(format) + " texture is not a complete render target");
    glViewport(0, 0, width, height);
    glDisable(GL_DITHER);  // dithering may change the UNORM conversion (GL ES 3.2 section 15.1.7)
    check("setup");
}

GlMultipass::~GlMultipass() {
    Impl& m = *impl_;
    glDeleteTextures(GLsizei(m.img.size()), m.img.data());
    glDeleteTextures(GLsizei(m.table.size()), m.table.data());
    glDeleteTextures(1, &m.scratch);
    glDeleteTextures(1, &m.fbTex);
    glDeleteFramebuffers(1, &m.fbo);
    glDeleteVertexArrays(1, &m.vao);
    glDeleteProgram(m.transfer);
    glDeleteProgram(m.blend);
    glDeleteProgram(m.combiner);
}

void GlMultipass::setCopyTexSubImage(bool on) { impl_->copy = on; }

double GlMultipass::copyMs(int count, int reps) {
    Impl& m = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
    m.target(m.fbTex);
    double best = 1e300;
    for (int r = 0; r < reps; ++r) {
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < count; ++i) {
            glActiveTexture(GL_TEXTURE0);
            glBindTexture(GL_TEXTURE_2D, m.img[i & 1 ? TexSI : TexTI]);
            glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, m.w, m.h);
        }
        glFinish();
        best = std::min(best, msSince(t0) / count);
    }
    check("copy timing");
    return best;
}

double GlMultipass::drawMs(int count, int reps) {
    Impl& m = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
    glBindVertexArray(m.vao);
    glViewport(0, 0, m.w, m.h);
    Pass p;
    p.op = Op::Transfer;
    p.scale = 0.5;
    double best = 1e300;
    for (int r = 0; r < reps; ++r) {
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < count; ++i) {
            p.src = i & 1 ? TexSI : TexTI;
            p.dst = i & 1 ? TexTI : TexSI;
            m.runTransfer(p);
        }
        glFinish();
        best = std::min(best, msSince(t0) / count);
    }
    check("draw timing");
    return best;
}

Image8 GlMultipass::run(const Program& prog, const Tables& tables, const Image8& s, const Image8& t,
                        const Image8& r, BlendArith arith, int frames, Timing* timing) {
    Impl& m = *impl_;
    if (prog.b != formatBits(m.fmt))
        throw std::invalid_argument("multipass: the program's b differs from the target format's bits");
    for (const Image8* im : {&s, &t, &r})
        if (im->width != m.w || im->height != m.h || im->px.size() != size_t(m.w) * m.h)
            throw std::invalid_argument("multipass: input image size differs from the context's");
    // (another user of the context, e.g. singlePassNoise, may have bound its own objects)
    glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
    glBindVertexArray(m.vao);
    glViewport(0, 0, m.w, m.h);
    Timing tm;
    glFinish();
    auto t0 = std::chrono::steady_clock::now();
    upload(m.img[TexS], m.w, m.h, s.px.data(), m.fmt);
    upload(m.img[TexT], m.w, m.h, t.px.data(), m.fmt);
    upload(m.img[TexR], m.w, m.h, r.px.data(), m.fmt);
    for (int i = 0; i < kTableCount; ++i) {
        std::vector<uint32_t> tb = tables[i];  // (b > 8: sran .. nran unused, zero)
        tb.resize(size_t(m.M) + 1, 0);
        upload(m.table[i], 256, (int(m.M) + 1) / 256, tb.data(), m.fmt);
    }
    glFinish();
    tm.msUpload = msSince(t0);
    check("upload");
    tm.draws = prog.draws();
    timeFrames(tm, frames, [&] {
        for (const Pass& p : prog.passes) {
            switch (p.op) {
                case Op::Transfer: m.runTransfer(p); break;
                case Op::Save: std::swap(m.img[p.dst], m.img[p.src]); break;
                case Op::Clear:
                    m.target(m.img[p.dst]);
                    glClearColor(p.k0 / m.M, p.k0 / m.M, p.k0 / m.M, 1.f);
                    glClear(GL_COLOR_BUFFER_BIT);
                    break;
                case Op::RcShiftLeft:
                case Op::RcIncWrap:
                case Op::RcBlendHiBit: m.runCombiner(p); break;
                default: m.runBlend(p, arith); break;
            }
        }
    });
    check("passes");
    t0 = std::chrono::steady_clock::now();
    m.target(m.img[TexNoise]);
    Image8 out{m.w, m.h, readback(m.w, m.h, m.fmt)};
    tm.msReadback = msSince(t0);
    check("readback");
    if (timing) *timing = tm;
    return out;
}


}  // namespace pst::gpu
