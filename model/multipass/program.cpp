// The SGI multipass noise program (Hart 2001, Figure 3 and section 4); see program.h.
#include "program.h"

#include <cstdlib>
#include <stdexcept>

namespace pst::multipass {

const char* imageName(int image) {
    static const char* const names[kImageCount] = {
        "tex_s", "tex_t", "tex_r", "tex_si", "tex_ti", "tex_ri", "tex_sf", "tex_tf", "tex_rf",
        "tex_sin", "tex_tin", "tex_rin", "tex_noise", "framebuffer", "tex_s1", "tex_t1", "tex_r1",
        "tex_scomp", "tex_tcomp", "tex_rcomp", "tex_corrnan", "tex_corrnanran", "tex_toff0", "tex_toff1",
        "tex_roff0", "tex_roff1"};
    return image >= 0 && image < kImageCount ? names[image] : "?";
}

const char* opName(Op op) {
    switch (op) {
        case Op::Transfer: return "transfer";
        case Op::BlendAdd: return "blend_add";
        case Op::BlendSub: return "blend_subtract";
        case Op::BlendMul: return "blend_multiply";
        case Op::BlendMulInv: return "blend_multiply_inverse";
        case Op::BlendXor: return "blend_xor";
        case Op::Save: return "savetex";
        case Op::Clear: return "clear";
        case Op::RcShiftLeft: return "rc_shift_left";
        case Op::RcIncWrap: return "rc_inc_wrap";
        case Op::RcBlendHiBit: return "rc_blend_hibit";
    }
    return "?";
}

int Program::draws() const {
    int n = 0;
    for (const Pass& p : passes) n += p.isDraw();
    return n;
}

double shiftRightBias(const Format& f) { return -(0.5 - 1.0 / (2 << f.bf)) / f.max(); }

double fracShift(const Format& f) { return double(f.max()) / ((1 << f.bf) - 1); }

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
    if (f.b != 8) throw std::invalid_argument("multipass: the SGI variant is built for b = 8");
    if (f.bf < 1 || f.bf > f.b)
        throw std::invalid_argument("multipass: b_f must be in 1.." + std::to_string(f.b));
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

RcConstants rcConstants(const Params& params) {
    // A stream apart from tables.h's (its first word differs from srand48's 0x330e).
    unsigned short state[3] = {0x5ec5, static_cast<unsigned short>(params.seed & 0xffff),
                               static_cast<unsigned short>(params.seed >> 16)};
    auto byte = [&] { return static_cast<int>(erand48(state) * 256); };
    RcConstants c;
    for (int a = 0; a < 3; ++a)
        for (int kk = 0; kk < 8; ++kk) c.ranzero[a][kk] = byte(), c.ranone[a][kk] = byte();
    for (int j = 0; j < 8; ++j) c.ranzero2[j] = byte(), c.ranone2[j] = byte();
    return c;
}

namespace {

Pass rc(Op op, int dst, int src, int k0 = 0, int k1 = 0, int alpha = 0) {
    Pass p;
    p.op = op;
    p.dst = dst;
    p.src = src;
    p.k0 = k0;
    p.k1 = k1;
    p.alpha = alpha;
    return p;
}

}  // namespace

Program rcProgram(const Params& params) {
    const Format& f = params.format;
    if (f.b != 8) throw std::invalid_argument("multipass: register combiners store 8 bits (b = 8)");
    if (f.bf < 1 || f.bf > f.b - 1)
        throw std::invalid_argument("multipass: register combiners need b_f in 1.." + std::to_string(f.b - 1));
    if (params.interp != Interp::Linear)
        throw std::invalid_argument("multipass: the register-combiner variant interpolates linearly (section 5)");
    const RcConstants c = rcConstants(params);
    const int bi = f.bi();
    Program prog;
    auto& P = prog.passes;
    const int coord[3] = {TexS, TexT, TexR}, plus1[3] = {TexS1, TexT1, TexR1},
              weight[3] = {TexSF, TexTF, TexRF}, comp[3] = {TexSComp, TexTComp, TexRComp};
    for (int a = 0; a < 3; ++a) {
        // The weight: b_i logical shifts left leave the fraction F at the top, F 2^b_i / 255
        // (= u 256/255 with u = F / 2^b_f the exact cell fraction; SGI's fracshift stretches
        // u to F / (2^b_f - 1) instead, which these shifts cannot). W and 1 - W sum to 1.
        int src = coord[a];
        for (int i = 0; i < bi; ++i) P.push_back(rc(Op::RcShiftLeft, weight[a], src)), src = weight[a];
        // The +1 corner: S + 2^b_f, or 0 where K = 2^b_i - 1 (S >= 256 - 2^b_f): its top b_i
        // bits are K + 1 mod 2^b_i, so the lattice wraps every 2^b_i cells as the SGI tables do.
        P.push_back(rc(Op::RcIncWrap, plus1[a], coord[a], 1 << f.bf, 256 - (1 << f.bf) - 32));
    }
    P.push_back(rc(Op::Clear, TexNoise, TexNoise));
    for (int k = 0; k < 8; ++k) {
        // 5.3's first loop: the b_i bits of each corner coordinate, high bit first; the
        // image of the corner's integer part is S itself (its top b_i bits are K) or tex_s1.
        int cur[3];
        for (int a = 0; a < 3; ++a) cur[a] = (k >> a & 1) ? plus1[a] : coord[a];
        P.push_back(rc(Op::Clear, TexCorrnan, TexCorrnan, RcConstants::start));
        for (int kk = 0; kk < bi; ++kk)
            for (int a = 0; a < 3; ++a) {
                P.push_back(rc(Op::RcBlendHiBit, TexCorrnan, cur[a], c.ranzero[a][kk], c.ranone[a][kk],
                               RcConstants::alpha));
                if (kk < bi - 1) P.push_back(rc(Op::RcShiftLeft, comp[a], cur[a])), cur[a] = comp[a];
            }
        // 5.3's second step: eight single-bit randomizations on the bits of tex_corrnan.
        P.push_back(rc(Op::Clear, TexCorrnanran, TexCorrnanran, RcConstants::start));
        for (int j = 0; j < 8; ++j) {
            P.push_back(rc(Op::RcBlendHiBit, TexCorrnanran, TexCorrnan, c.ranzero2[j], c.ranone2[j],
                           RcConstants::alpha));
            if (j < 7) P.push_back(rc(Op::RcShiftLeft, TexCorrnan, TexCorrnan));
        }
        // Weights (two textures per pass on a GeForce2: one multiply each), then the sum.
        for (int a = 0; a < 3; ++a)
            P.push_back(blend((k >> a & 1) ? Op::BlendMul : Op::BlendMulInv, TexCorrnanran, weight[a]));
        P.push_back(blend(Op::BlendAdd, TexCorrnanran, TexNoise));
        P.push_back(blend(Op::Save, TexNoise, TexCorrnanran));
    }
    return prog;
}

Program xorProgram(const Params& params) {
    const Format& f = params.format;
    if (f.b < 8 || f.b > 24) throw std::invalid_argument("multipass: the exclusive-or variant needs b in 8..24");
    // The offset index K + 65 must fit: b_i <= 7 at b = 8; 2^b_i + 65 <= 2^b - 1 above.
    if (f.bf < 1 || f.bi() < 1 || (1 << f.bi()) + 65 > f.max())
        throw std::invalid_argument("multipass: the exclusive-or variant needs b_f >= 1 and 2^b_i + 65 < 2^b");
    const double M = f.max();
    Program prog;
    prog.b = f.b;
    auto& P = prog.passes;
    const int coord[3] = {TexS, TexT, TexR}, integer[3] = {TexSI, TexTI, TexRI},
              weight[3] = {TexSF, TexTF, TexRF};
    // Rayshade's lattice index is floor(x) + 1e6; the hash reads its low 8 bits: K + 64 (+1).
    // K + 65 <= 2^b_i + 64 < 256, so the offsets never wrap.
    const int off = 1000000 & 255;
    for (int a = 0; a < 3; ++a) {
        P.push_back(transfer(integer[a], coord[a], 1.0 / f.shift(), shiftRightBias(f)));
        P.push_back(transfer(Fb, integer[a], f.shift()));
        P.push_back(blend(Op::BlendSub, Fb, coord[a]));
        // Rayshade's weight u = F / 2^b_f: scale M / 2^b_f (M = 2^b - 1). F M / 2^b_f is a multiple of
        // 2^-b_f and hits a rounding tie at F = 2^(b_f - 1); a bias of 2^-(b_f + 1) LSB rounds
        // those up and keeps every value 2^-(b_f + 1) LSB from a tie.
        P.push_back(transfer(weight[a], Fb, M / f.shift(), 1.0 / (2 << f.bf) / M));
        if (params.interp == Interp::Scurve) {
            P.push_back(transfer(Fb, weight[a], -0.5, 0.75));
            P.push_back(blend(Op::BlendMul, Fb, weight[a]));
            P.push_back(blend(Op::BlendMul, Fb, weight[a]));
            P.push_back(transfer(weight[a], Fb, 4.0));
        }
    }
    const int offImg[2][2] = {{TexTOff0, TexTOff1}, {TexROff0, TexROff1}};
    for (int a = 1; a < 3; ++a)
        for (int bit = 0; bit < 2; ++bit)
            P.push_back(transfer(offImg[a - 1][bit], integer[a], 1.0, (off + bit) / M));
    P.push_back(blend(Op::Clear, TexNoise, TexNoise));
    for (int k = 0; k < 8; ++k) {
        const int bs = k & 1, bt = k >> 1 & 1, br = k >> 2 & 1;
        P.push_back(transfer(Fb, TexSI, 1.0, (off + bs) / M, Perm));  // P[i]
        P.push_back(blend(Op::BlendXor, Fb, offImg[0][bt]));               // ^ j
        P.push_back(transfer(Fb, Fb, 1.0, 0.0, Perm));                     // P[.]
        P.push_back(blend(Op::BlendXor, Fb, offImg[1][br]));               // ^ k
        P.push_back(transfer(Fb, Fb, 1.0, 0.0, ValuePerm));                // V[P[.]]
        for (int a = 0; a < 3; ++a)
            P.push_back(blend((k >> a & 1) ? Op::BlendMul : Op::BlendMulInv, Fb, weight[a]));
        P.push_back(blend(Op::BlendAdd, Fb, TexNoise));
        P.push_back(blend(Op::Save, TexNoise, Fb));
    }
    return prog;
}

Program makeProgram(const Params& params) {
    switch (params.variant) {
        case Variant::Rc: return rcProgram(params);
        case Variant::Xor: return xorProgram(params);
        default: return sgiProgram(params);
    }
}

}  // namespace pst::multipass
