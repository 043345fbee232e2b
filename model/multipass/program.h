// Perlin noise as a multipass pixel shader: Hart, "Perlin Noise Pixel Shaders", Graphics
// Hardware 2001 (the seed's third paper), the SGI algorithm of its section 4.
//
// The algorithm is a Program: a list of Passes over 8-bit luminance images (the paper's
// textures tex_s, tex_si, tex_sf, ... and the framebuffer). Each pass is exactly one of the
// paper's operations: a PixelTransfer scale and bias with an optional PixelMap lookup, a
// blend (add, subtract, multiply by SRC or 1 - SRC), or a savetex. Two executors run the same
// Program: the bit-accurate CPU model (cpu_model.h, the GL specification's UNORM arithmetic
// in integers and doubles) and OpenGL ES 3 through EGL (testbench/gpu/, shaders and blending).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace pst::multipass {

// Section 3: a coordinate is a b-bit channel value, fixed point with b_i integer and b_f
// fractional bits (b = b_i + b_f). The framebuffer here is RGBA8 as in the paper: b = 8.
struct Format {
    static constexpr int b = 8;
    int bf = 4;  // the paper's Figure 4 uses b_f = 4
    int bi() const { return b - bf; }
    int shift() const { return 1 << bf; }  // section 4.2: shift = 1 << b_f
};

// Interpolation of the corner values: linear (Figure 3) or SCURVE(u) = uu(3 - 2u) by four
// extra passes per weight image (section 7).
enum class Interp { Linear, Scurve };

struct Params {
    Format format;
    Interp interp = Interp::Linear;
    uint32_t seed = 1;  // the random tables' stream (tables.h)
};

// The images (textures) the passes read and write, named as in section 4.
enum Image : int {
    TexS, TexT, TexR,        // input coordinates, b_i.b_f fixed point (section 4.1)
    TexSI, TexTI, TexRI,     // integer parts, shifted right by b_f (section 4.2)
    TexSF, TexTF, TexRF,     // weights: fractional parts scaled to [0, 1] (section 4.2)
    TexSIn, TexTIn, TexRIn,  // random values of the corner's coordinates (section 4.3)
    TexNoise,                // the running sum (Figure 3's noise)
    Fb,                      // the framebuffer the blends accumulate in
    kImageCount
};
const char* imageName(int image);

// The paper's tables (section 4.3): sran, tran, rran (uniform in [0, 1/3]) and nran.
enum Table : int { Sran, Tran, Rran, Nran, kTableCount, NoTable = -1 };

enum class Op {
    Transfer,     // dst = map(clamp(scale src + bias)): blendtex with PixelTransfer (scale, bias)
                  // and, if table != NoTable, PixelMap(table) (section 4.1); dst may be src
    BlendAdd,     // dst = clamp(dst + src):  BlendFunc(ONE, ONE)
    BlendSub,     // dst = clamp(src - dst):  BlendEquation(SUBTRACT), BlendFunc(ONE, ONE) (4.2)
    BlendMul,     // dst = dst src:           BlendFunc(ZERO, SRC_COLOR)   (section 4.3, weights)
    BlendMulInv,  // dst = dst (1 - src):     BlendFunc(ZERO, ONE_MINUS_SRC_COLOR)
    Save,         // savetex: dst = src, src undefined afterwards (render to texture: a rename)
    Clear,        // dst = black ("Initialize texture noise = black", Figure 3)
};
const char* opName(Op op);

struct Pass {
    Op op = Op::Transfer;
    int dst = Fb;
    int src = Fb;
    double scale = 1.0, bias = 0.0;  // Transfer only
    int table = NoTable;             // Transfer only
    bool isDraw() const { return op != Op::Save && op != Op::Clear; }
};

struct Program {
    std::vector<Pass> passes;
    int draws() const;  // passes that draw (the paper's pass count); Save and Clear do not
};

// Section 4 as a Program (Figure 3 with section 4.2's shifts and section 4.3's randomization):
// per coordinate 4 passes (+4 with SCURVE), per corner 11 passes: 100 draws linear, 112 SCURVE.
Program sgiProgram(const Params& params);

// Section 4.2's shift right: the paper rounds with a PixelTransfer bias of -0.5/255 where the
// hardware rounds instead of truncating. The GL specification's float -> UNORM conversion
// rounds to nearest but leaves ties to the driver, and -0.5/255 puts every coordinate with a
// zero fraction exactly on a tie; we bias by -(0.5 - 2^-(b_f+1))/255 instead, which gives
// floor(S / 2^b_f) with every value at least 2^-(b_f+1) of an LSB away from a tie.
double shiftRightBias(const Format& f);
// Section 4.2's fracshift = 255 / ((1 << b_f) - 1): the fraction scaled to a [0, 1] weight.
double fracShift(const Format& f);

}  // namespace pst::multipass
