// pst eval: texture block + fragment file -> f, grad_s f, w, filtered RGBA per fragment, through
// the reference (double), the golden model (fixed point) or the verilated RTL.
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "common.h"
#include "driver.h"
#include "fixed.h"
#include "fragments.h"
#include "imageio.h"

namespace pst::cli {
namespace {

struct EvalArgs {
    std::string texPath, fragPath, out, filterName, model = "reference";
    bool quiet = false;
};

void emit(const std::string& outPath, const std::string& text) {
    if (outPath.empty() || outPath == "-") {
        std::cout << text;
        return;
    }
    Outputs outputs;   // the whole file, or none
    writeTextFile(outputs.file("-o", outPath), text);
    outputs.commit();
}

int runEval(const EvalArgs& a, const HwArgs& hw) {
    Texture tex = loadTexture(a.texPath);
    FilterKind kind = tex.filter;
    if (!a.filterName.empty() && !parseFilterKind(a.filterName, &kind))
        throw InputError("--filter: unknown filter '" + a.filterName + "' (expected none, mip, mip_linear, sat, box or trapezoid)");
    const auto frags = loadFragments(a.fragPath);
    std::ostringstream os;
    char buf[512];
    if (a.model != "reference") {
        // The hardware models: same columns, from the fixed-point values.
        if (hw.profiles.size() != 1) throw InputError("--profile: eval takes exactly one profile");
        const Profile p = profileByName(hw.profiles[0], a.model == "rtl");
        tex.filter = kind;
        TextureProgram prog = programTexture(p, tex);
        std::vector<FragmentFx> in;
        for (size_t i = 0; i < frags.size(); ++i)
            in.push_back(quantizeFragment(p, uint32_t(i), frags[i].s, frags[i].dsdx, frags[i].dsdy));
        GoldenPipeline golden(p);
        for (const auto& [addr, d] : prog.writes) golden.write(addr, d);
        std::vector<PixelFx> out;
        for (const auto& f : in) out.push_back(golden.eval(f));
        if (a.model == "rtl") {
            auto rtl = makeRtlModel(p.name, hw.sim);
            rtl->write(prog.writes);
            std::vector<PixelFx> got = rtl->run(in, prog.activeOctaves);
            size_t bad = 0;
            for (size_t i = 0; i < got.size(); ++i) bad += !(got[i] == out[i]);
            if (bad) std::cerr << "warning: rtl differs from golden at " << bad << " of " << got.size() << " fragments\n";
            out = got;
        }
        os << "# f  df/ds df/dt df/dr  w  r g b a   (texture " << a.texPath << ", profile " << p.name << ", model "
           << a.model << ", filter code " << prog.filterKind << ")\n";
        for (const auto& px : out) {
            const glm::dvec4 c = unpackRgba(p, px.rgba);
            std::snprintf(buf, sizeof buf, "%.17g  %.17g %.17g %.17g  %.17g  %.17g %.17g %.17g %.17g\n",
                          fx::toDouble(px.f, p.f.fracBits), fx::toDouble(px.grad[0], p.grad.fracBits),
                          fx::toDouble(px.grad[1], p.grad.fracBits), fx::toDouble(px.grad[2], p.grad.fracBits),
                          fx::toDouble(px.w, p.widthFrac) / p.clutSize(), c.r, c.g, c.b, c.a);
            os << buf;
        }
        emit(a.out, os.str());
        return 0;
    }
    os << "# f  df/ds df/dt df/dr  w  r g b a   (texture " << a.texPath << ", filter " << toString(kind) << ")\n";
    for (const auto& fr : frags) {
        const TextureSample t = shade(tex, fr.s, fr.dsdx, fr.dsdy, kind);
        std::snprintf(buf, sizeof buf, "%.17g  %.17g %.17g %.17g  %.17g  %.17g %.17g %.17g %.17g\n", t.f,
                      t.gradS.x, t.gradS.y, t.gradS.z, t.filterWidth, t.rgba.r, t.rgba.g, t.rgba.b, t.rgba.a);
        os << buf;
    }
    emit(a.out, os.str());
    return 0;
}

}  // namespace

Command registerEval(CLI::App& app) {
    auto a = std::make_shared<EvalArgs>();
    auto hw = std::make_shared<HwArgs>();
    auto* eval = app.add_subcommand("eval", "Evaluate a texture at the fragments of a fragment file");
    eval->add_option("-t,--texture", a->texPath, "Texture block (TOML, the keys of [textures.NAME])")->required()->check(CLI::ExistingFile);
    eval->add_option("-f,--fragments", a->fragPath, "Fragment file: s t r ds/dx dt/dx dr/dx ds/dy dt/dy dr/dy per line")->required()->check(CLI::ExistingFile);
    eval->add_option("-o,--out", a->out, "Output file (default stdout)");
    eval->add_option("--filter", a->filterName, "Override the texture's filter: none, mip, mip_linear, sat, box, trapezoid "
                     "(default: the texture's)");
    eval->add_option("--model", a->model, "reference (double), golden (fixed point) or rtl (verilated)")
        ->check(CLI::IsMember({"reference", "golden", "rtl"}));
    eval->add_option("--profile", hw->profiles, profileHelp("Hardware profile for --model golden|rtl (default full)"))
        ->allow_extra_args(false);
    eval->add_flag("-q,--quiet", a->quiet, "Nothing on stderr but errors and warnings (eval prints no progress)");
    return {eval, [a, hw, eval]() {
                if (a->model == "reference")
                    refuseGiven(eval, {"--profile"}, "needs --model golden or rtl (the reference model has no profile)");
                if (a->model != "reference" && hw->profiles.empty()) hw->profiles = {"full"};
                checkOutFile("-o", a->out);
                checkNotInput("-o", a->out, {a->texPath, a->fragPath});
                return runEval(*a, *hw);
            }};
}

}  // namespace pst::cli
