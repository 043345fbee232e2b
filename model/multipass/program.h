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
// fractional bits (b = b_i + b_f). The framebuffer is RGBA8 as in the paper (b = 8); section
// 6.1's precision proposal runs the exclusive-or variant at b = 10 (RGB10_A2), 16 (R16) and 24
// (the packed 24-bit luminance, CPU model only).
struct Format {
    int b = 8;
    int bf = 4;  // the paper's Figure 4 uses b_f = 4
    int bi() const { return b - bf; }
    int shift() const { return 1 << bf; }  // section 4.2: shift = 1 << b_f
    int max() const { return (1 << b) - 1; }  // the UNORM scale: value v means v / max
};

// Interpolation of the corner values: linear (Figure 3) or SCURVE(u) = uu(3 - 2u) by four
// extra passes per weight image (section 7).
enum class Interp { Linear, Scurve };

// Which of the paper's implementations: section 4's SGI PixelTransfer/PixelMap program, or
// section 5's GeForce2 register-combiner program (bit-serial randomization, Gaussian noise).
// Xor: section 6.3's proposal, exclusive-or blending (GLSL integer operations here; GLES has no
// glLogicOp): the lattice index hashed as the chip's 8-bit hash (model/noise.h, Perm256:
// P[P[P[i] ^ j] ^ k] of the lattice indices after Rayshade's 1e6 offset) by PixelMap lookups
// and XOR blends, the value 0.5 R[m] + 1/2 by one more lookup: Rayshade's value noise
// (NoiseHash::Perm256, corners Value) pointwise, in 8 bits.
enum class Variant { Sgi, Rc, Xor };

struct Params {
    Format format;
    Interp interp = Interp::Linear;
    Variant variant = Variant::Sgi;
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
    // Register-combiner variant (section 5) only:
    TexS1, TexT1, TexR1,     // the +1 corners' integer images: (K + 1 mod 2^b_i) << b_f
    TexSComp, TexTComp, TexRComp,  // tex_comp[comp]: the corner's integer image being shifted
    TexCorrnan,              // tex_corrnan: 12 single-bit randomizations of the corner (5.3)
    TexCorrnanran,           // tex_corrnanran: 8 more, on the bits of tex_corrnan (5.3)
    // Exclusive-or variant only: t and r integer parts + Rayshade's offset (+1 for the far corner)
    TexTOff0, TexTOff1, TexROff0, TexROff1,
    kImageCount
};
const char* imageName(int image);

// The paper's tables (section 4.3): sran, tran, rran (uniform in [0, 1/3]) and nran.
// Perm: Rayshade's 256-entry permutation (model/noise.h NoiseTables::perm); ValuePerm:
// the byte round((0.5 R[P[m]] + 1/2) 255), the last lookup of the Xor variant.
enum Table : int { Sran, Tran, Rran, Nran, Perm, ValuePerm, kTableCount, NoTable = -1 };

enum class Op {
    Transfer,     // dst = map(clamp(scale src + bias)): blendtex with PixelTransfer (scale, bias)
                  // and, if table != NoTable, PixelMap(table) (section 4.1); dst may be src
    BlendAdd,     // dst = clamp(dst + src):  BlendFunc(ONE, ONE)
    BlendSub,     // dst = clamp(src - dst):  BlendEquation(SUBTRACT), BlendFunc(ONE, ONE) (4.2)
    BlendMul,     // dst = dst src:           BlendFunc(ZERO, SRC_COLOR)   (section 4.3, weights)
    BlendMulInv,  // dst = dst (1 - src):     BlendFunc(ZERO, ONE_MINUS_SRC_COLOR)
    BlendXor,     // dst = dst ^ src (bytes): LogicOp(XOR), section 6.3's proposal
    Save,         // savetex: dst = src, src undefined afterwards (render to texture: a rename)
    Clear,        // dst = the byte k0 (0: "Initialize texture noise = black", Figure 3)
    // Register combiners (section 5, NV_register_combiners on a GeForce2: two general
    // combiner stages and the final combiner per pass, tex0 = src, tex1 = dst). Arithmetic in
    // cpu_model.h (rc* functions): 9-bit signed internal values on the 1/255 grid.
    RcShiftLeft,  // section 5.2's logical shift left: dst = 2 (src < 1/2 ? src : src - 1/2)
    RcIncWrap,    // dst = (src >= k1 + 32 ? 0 : src + k0): the +1 corner with the lattice wrap
    RcBlendHiBit, // section 5.3's setupblendhibit + blend2tex: c = hibit(src) ? k1 : k0,
                  // dst = alpha c + (1 - alpha) dst (final combiner; alpha = 1/8 in the paper)
};
const char* opName(Op op);

struct Pass {
    Op op = Op::Transfer;
    int dst = Fb;
    int src = Fb;
    double scale = 1.0, bias = 0.0;  // Transfer only
    int table = NoTable;             // Transfer only
    int k0 = 0, k1 = 0, alpha = 0;   // constant bytes: Clear (k0) and the Rc* ops
    bool isDraw() const { return op != Op::Save && op != Op::Clear; }
};

struct Program {
    int b = 8;  // the images' UNORM bits (Format::b)
    std::vector<Pass> passes;
    int draws() const;  // passes that draw (the paper's pass count); Save and Clear do not
};

// Section 4 as a Program (Figure 3 with section 4.2's shifts and section 4.3's randomization):
// per coordinate 4 passes (+4 with SCURVE), per corner 11 passes: 100 draws linear, 112 SCURVE.
Program sgiProgram(const Params& params);

// Section 5's random luminances: ranzero[comp][kk], ranone[comp][kk] (the b_i bits of each of
// the three integer coordinates, 5.3's first loop) and ranzero2[j], ranone2[j] (the eight
// bits of tex_corrnan, 5.3's second step). Bytes uniform in 0..255 from erand48(seed).
struct RcConstants {
    std::array<std::array<int, 8>, 3> ranzero{}, ranone{};
    std::array<int, 8> ranzero2{}, ranone2{};
    static constexpr int alpha = 32;  // 5.3: "the alpha channel of rgba0 and rgba1 to 1/8": round(255/8)
    static constexpr int start = 128; // the accumulators start at grey (a clear, not a pass)
};
RcConstants rcConstants(const Params& params);

// Section 5 as a Program (b_f in 1..7). Per axis: b_i shifts left (the weight F << b_i) and
// one RcIncWrap (the +1 corner); per corner: 3 b_i randoms + 3 (b_i - 1) shifts, 8 randoms +
// 7 shifts, 3 weight multiplies, 1 add. b_f = 4: 15 + 8 x 40 = 335 draws (the paper: 375).
Program rcProgram(const Params& params);

// Section 6.3's proposal as a Program (b_f in 1..7): the SGI decomposition with the weight
// u = F / 2^b_f (Rayshade's), per axis t, r two offset images, per corner 9 draws: P lookup, XOR,
// P, XOR, V(P) lookup, 3 weights, the add. 12 + 4 + 72 = 88 draws (+12 with SCURVE).
Program xorProgram(const Params& params);

// The variant's program (params.variant); SCURVE is not the register combiners'.
Program makeProgram(const Params& params);

// Section 4.2's shift right: the paper rounds with a PixelTransfer bias of -0.5/255 where the
// hardware rounds instead of truncating. The GL specification's float -> UNORM conversion
// rounds to nearest but leaves ties to the driver, and -0.5/255 puts every coordinate with a
// zero fraction exactly on a tie; we bias by -(0.5 - 2^-(b_f+1))/255 instead, which gives
// floor(S / 2^b_f) with every value at least 2^-(b_f+1) of an LSB away from a tie.
double shiftRightBias(const Format& f);
// Section 4.2's fracshift = 255 / ((1 << b_f) - 1): the fraction scaled to a [0, 1] weight.
double fracShift(const Format& f);

}  // namespace pst::multipass
