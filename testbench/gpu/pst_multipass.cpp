// pst_multipass: Perlin noise as a multipass pixel shader (Hart 2001, section 4) on OpenGL ES 3
// through EGL without a display. Draws the noise of the plane of Figure 4 (s, t over the image,
// r fixed), times the passes, checks the result against the bit-accurate CPU model and
// measures it against the paper's Figure 3 in double and Rayshade's noise. docs/MULTIPASS.md.
//
//   pst_multipass --size 256 --variant sgi --out noise.png --json timing.json
// Exit 0, 1 when --check finds a difference, 2 on bad arguments or no EGL device.
#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "cpu_model.h"
#include "egl_context.h"
#include "gl_multipass.h"
#include "noise.h"
#include "quality.h"

using namespace pst::multipass;
using pst::gpu::loadAverage;
using pst::gpu::BlendArith;

namespace {

struct Moments {
    double sum = 0, sq = 0;
    size_t n = 0;
    void add(double v) { sum += v, sq += v * v, ++n; }
    double mean() const { return sum / n; }
    double stddev() const { return std::sqrt(std::max(0.0, sq / n - mean() * mean())); }
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Perlin noise as a multipass pixel shader (Hart 2001) on OpenGL ES 3 via EGL"};
    int size = 256, bf = 4, frames = 10;
    uint32_t seed = 1;
    double r = 0.0;
    std::string variant = "sgi", interp = "linear", arith = "shader", out, json;
    bool check = false;
    app.add_option("--size", size, "image width and height (pixels)")->check(CLI::Range(1, 4096));
    app.add_option("--variant", variant, "pass algorithm: sgi (section 4), rc (section 5, register combiners) or xor (section 6.3, exclusive-or hash)")
        ->check(CLI::IsMember({"sgi", "rc", "xor"}));
    app.add_option("--bf", bf, "fraction bits b_f of the 8-bit coordinates (b_i = 8 - b_f)")->check(CLI::Range(1, 8));
    app.add_option("--interp", interp, "linear (Figure 3) or scurve (section 7, 4 more passes per axis)")
        ->check(CLI::IsMember({"linear", "scurve"}));
    app.add_option("--arith", arith, "blends as shader (specified exactly) or blend (glBlendFunc, the paper's)")
        ->check(CLI::IsMember({"shader", "blend"}));
    app.add_option("--seed", seed, "random tables' seed");
    app.add_option("--r", r, "the fixed r coordinate of the s, t plane");
    app.add_option("--frames", frames, "frames timed")->check(CLI::Range(1, 10000));
    app.add_option("--out", out, "noise image (PNG, 8-bit grey)");
    app.add_option("--json", json, "timing, pass counts and quality as JSON");
    app.add_flag("--check", check, "compare with the CPU model bit for bit (exit 1 on a difference)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }

    Params params;
    params.format.bf = bf;
    params.interp = interp == "scurve" ? Interp::Scurve : Interp::Linear;
    params.seed = seed;
    params.variant = variant == "rc" ? Variant::Rc : variant == "xor" ? Variant::Xor : Variant::Sgi;
    const Format& f = params.format;
    // Figure 4's plane: s, t from 0 to 2^b_i over the image (every byte value at size 256), r fixed.
    Image8 s{size, size, {}}, t = s, rr = s;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            s.px.push_back(uint8_t(x * 256 / size));
            t.px.push_back(uint8_t(y * 256 / size));
            rr.px.push_back(toFixed(r, f));
        }
    Program prog;
    try {
        prog = makeProgram(params);
    } catch (const std::invalid_argument& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
    const Tables tables = makeTables(params);
    nlohmann::json j;
    Image8 noise;
    pst::gpu::Timing timing;
    try {
        pst::gpu::EglContext ctx;
        pst::gpu::GlMultipass gl(size, size);
        gl.run(prog, tables, s, t, rr, arith == "blend" ? BlendArith::Blend : BlendArith::Shader);  // warm-up
        noise = gl.run(prog, tables, s, t, rr, arith == "blend" ? BlendArith::Blend : BlendArith::Shader,
                       frames, &timing);
        j["renderer"] = ctx.renderer();
        j["gl_version"] = ctx.version();
        j["egl_platform"] = ctx.platform();
    } catch (const pst::gpu::EglUnavailable& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
    j["variant"] = variant;
    j["size"] = size;
    j["b"] = f.b;
    j["b_i"] = f.bi();
    j["b_f"] = f.bf;
    j["interp"] = interp;
    j["arith"] = arith;
    j["seed"] = seed;
    j["draws_per_frame"] = timing.draws;
    j["frames"] = timing.frames;
    j["ms_per_frame"] = timing.msPerFrame;
    j["ms_per_frame_min"] = timing.msPerFrameMin;
    j["ms_per_draw"] = timing.msPerFrame / timing.draws;
    j["load_average_1min"] = loadAverage();
    j["ms_upload"] = timing.msUpload;
    j["ms_readback"] = timing.msReadback;

    // The CPU model, and quality: against Figure 3 in double (the 8-bit passes' error) and the
    // statistics of Rayshade's noise on the same plane (value corners, same interpolation:
    // the lattice values differ, so only the distributions compare).
    Stats stats;
    const Image8 cpu = runCpu(prog, tables, s, t, rr, &stats);
    size_t differ = 0;
    for (size_t i = 0; i < cpu.px.size(); ++i) differ += cpu.px[i] != noise.px[i];
    j["cpu_model_pixels_differing"] = differ;
    j["min_tie_margin_lsb"] = stats.minTieMargin;
    double sq = 0, maxErr = 0;
    Moments mp, ray;
    pst::NoiseOptions ro;
    ro.interp = params.interp == Interp::Scurve ? pst::NoiseInterp::Scurve : pst::NoiseInterp::Linear;
    ro.corner = pst::NoiseCorner::Value;
    const RcConstants rcc = rcConstants(params);
    for (size_t i = 0; i < noise.px.size(); ++i) {
        const int c[3] = {int(s.px[i]), int(t.px[i]), int(rr.px[i])};
        const double ideal = idealNoise(params, tables, rcc, c[0], c[1], c[2]);
        const double e = noise.px[i] / 255.0 - ideal;
        sq += e * e;
        maxErr = std::max(maxErr, std::fabs(e));
        mp.add(noise.px[i] / 255.0);
        // Rayshade's value noise is 0.5 R in [-0.5, 0.5]: shifted to [0, 1]
        ray.add(pst::noise(glm::dvec3(c[0], c[1], c[2]) / double(1 << f.bf), ro) + 0.5);
    }
    j["rms_vs_figure3_double"] = std::sqrt(sq / noise.px.size());
    j["max_vs_figure3_double"] = maxErr;
    j["mean"] = mp.mean();
    j["stddev"] = mp.stddev();
    j["rayshade_value_noise_mean"] = ray.mean();
    j["rayshade_value_noise_stddev"] = ray.stddev();

    if (!out.empty()) {
        auto img = OIIO::ImageOutput::create(out);
        OIIO::ImageSpec spec(size, size, 1, OIIO::TypeDesc::UINT8);
        const std::vector<uint8_t> bytes(noise.px.begin(), noise.px.end());
        if (!img || !img->open(out, spec) || !img->write_image(OIIO::TypeDesc::UINT8, bytes.data()) ||
            !img->close()) {
            std::cerr << "error: cannot write " << out << "\n";
            return 2;
        }
    }
    if (!json.empty()) {
        std::ofstream o(json);
        o << j.dump(2) << "\n";
        if (!o) {
            std::cerr << "error: cannot write " << json << "\n";
            return 2;
        }
    }
    std::printf("%s %s b_f %d %s, %dx%d on %s: %d draws, %.2f ms/frame (min %.2f, %.3f ms/draw); "
                "rms vs Figure 3 %.2f LSB; %zu pixels differ from the CPU model\n",
                variant.c_str(), interp.c_str(), f.bf, arith.c_str(), size, size,
                j["renderer"].get<std::string>().c_str(), timing.draws, timing.msPerFrame,
                timing.msPerFrameMin, timing.msPerFrame / timing.draws, std::sqrt(sq / noise.px.size()) * 255, differ);
    return check && differ ? 1 : 0;
}
