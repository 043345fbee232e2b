// The SGI multipass noise program (Hart 2001, Figure 3 and section 4); see program.h.
#include "program.h"

#include <stdexcept>

namespace pst::multipass {

const char* imageName(int image) {
    static const char* const names[kImageCount] = {
        "tex_s", "tex_t", "tex_r", "tex_si", "tex_ti", "tex_ri", "tex_sf", "tex_tf", "tex_rf",
        "tex_sin", "tex_tin", "tex_rin", "tex_noise", "framebuffer"};
    return image >= 0 && image < kImageCount ? names[image] : "?";
}

const char* opName(Op op) {
    switch (op) {
        case Op::Transfer: return "transfer";
        case Op::BlendAdd: return "blend_add";
        case Op::BlendSub: return "blend_subtract";
        case Op::BlendMul: return "blend_multiply";
        case Op::BlendMulInv: return "blend_multiply_inverse";
        case Op::Save: return "savetex";
        case Op::Clear: return "clear";
    }
    return "?";
}

int Program::draws() const {
    int n = 0;
    for (const Pass& p : passes) n += p.isDraw();
    return n;
}

double shiftRightBias(const Format& f) { return -(0.5 - 1.0 / (2 << f.bf)) / 255.0; }

double fracShift(const Format& f) { return 255.0 / ((1 << f.bf) - 1); }

namespace {

Pass transfer(int dst, int src, double scale, double bias = 0.0, int table = NoTable) {
    Pass p;
    p.op = Op::Transfer;
    p.dst = dst;
    p.src = src;
    p.scale = scale;
    p.bias = bias;
    p.table = table;
    return p;
}

Pass blend(Op op, int dst, int src) {
    Pass p;
    p.op = op;
    p.dst = dst;
    p.src = src;
    return p;
}

}  // namespace

Program sgiProgram(const Params& params) {
    const Format& f = params.format;
    if (f.bf < 1 || f.bf > Format::b)
        throw std::invalid_argument("multipass: b_f must be in 1.." + std::to_string(Format::b));
    Program prog;
    auto& P = prog.passes;
    const int coord[3] = {TexS, TexT, TexR}, integer[3] = {TexSI, TexTI, TexRI},
              weight[3] = {TexSF, TexTF, TexRF}, random[3] = {TexSIn, TexTIn, TexRIn};
    // Section 4.2: decompose each coordinate into its integer part and its weight.
    for (int a = 0; a < 3; ++a) {
        // shift s right to remove the fractional part, save as si
        P.push_back(transfer(integer[a], coord[a], 1.0 / f.shift(), shiftRightBias(f)));
        // shift si back left
        P.push_back(transfer(Fb, integer[a], f.shift()));
        // subtract si << b_f from s: the fractional part (BlendEquation(SUBTRACT): src - dst)
        P.push_back(blend(Op::BlendSub, Fb, coord[a]));
        // scale the fractional part into a normalized weight in [0, 1]
        P.push_back(transfer(weight[a], Fb, fracShift(f)));
        if (params.interp == Interp::Scurve) {
            // Section 7: SCURVE(u) / 4 = u u (3/4 - u/2), modulated, then scaled by 4.
            P.push_back(transfer(Fb, weight[a], -0.5, 0.75));
            P.push_back(blend(Op::BlendMul, Fb, weight[a]));
            P.push_back(blend(Op::BlendMul, Fb, weight[a]));
            P.push_back(transfer(weight[a], Fb, 4.0));
        }
    }
    // Figure 3: noise = black, then the eight corners.
    P.push_back(blend(Op::Clear, TexNoise, TexNoise));
    const int tables[3] = {Sran, Tran, Rran};
    for (int k = 0; k < 8; ++k) {
        // Section 4.3: tex_sin = sran(si) or sran(si + 1) (PixelTransfer bias 1/255, PixelMap)
        for (int a = 0; a < 3; ++a)
            P.push_back(transfer(random[a], integer[a], 1.0, (k >> a & 1) ? 1.0 / 255.0 : 0.0, tables[a]));
        // add them up into a single random number, then one more randomization (in place)
        P.push_back(transfer(Fb, TexSIn, 1.0));
        P.push_back(blend(Op::BlendAdd, Fb, TexTIn));
        P.push_back(blend(Op::BlendAdd, Fb, TexRIn));
        P.push_back(transfer(Fb, Fb, 1.0, 0.0, Nran));
        // weight by the fractional parts: BlendFunc(0, (k&1) ? SRC : 1 - SRC) per axis
        for (int a = 0; a < 3; ++a)
            P.push_back(blend((k >> a & 1) ? Op::BlendMul : Op::BlendMulInv, Fb, weight[a]));
        // add the corner into the noise sum and keep track of it (savetex)
        P.push_back(blend(Op::BlendAdd, Fb, TexNoise));
        P.push_back(blend(Op::Save, TexNoise, Fb));
    }
    return prog;
}

}  // namespace pst::multipass
