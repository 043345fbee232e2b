// pst_multipass_study: the measurements of docs/MULTIPASS.md's generated sections, as one JSON
// record (docs/data/multipass.json; scripts/gen_docs.py renders it, scripts/pstlib/docs/multipass_doc.py).
//
//   build/pst_multipass_study --out docs/data/multipass.json [--frames 5] [--quick]
//
// quality: per variant (sgi linear, sgi scurve, rc) and b_f = 1..7 (b = 8): the noise of the
//   passes on OpenGL ES (checked against the CPU model) at random coordinates, against Figure 3
//   in double on the variant's own lattice (what 8 bits and b_f cost), against Rayshade's value
//   noise (model/noise.h, linear, corners Value) and the chip's golden noise (model/golden,
//   profile balanced with noise interp linear, corner value) at the same points: moments,
//   excess kurtosis (white/uniform -1.2, Gaussian 0), a histogram, the Kolmogorov-Smirnov
//   distance between distributions; and the lattice correlations of Figures 6 and 11.
// proposals (section 6): per configuration (variant; render to texture or glCopyTexSubImage2D
//   after every draw; the single-pass shader) at 256 x 256 and 1024 x 1024: draws, the minimum
//   over --frames frames of the passes' time (glFinish to glFinish; the machine is shared, so
//   the min, with the load average), pixels differing from the CPU model, RMS vs Figure 3 in
//   double on the variant's lattice and, where the lattice is Rayshade's (xor, single pass),
//   pointwise RMS vs Rayshade's value noise with the 8-bit hash (model/noise.h Perm256).
// Exit 0, 1 when the GL output differs from the CPU model, 2 on errors (no EGL device).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>

#include "cpu_model.h"
#include "egl_context.h"
#include "gl_multipass.h"
#include "noise.h"
#include "noise_fx.h"
#include "profile.h"
#include "quality.h"
#include "source_dir.h"

using namespace pst::multipass;
using pst::gpu::loadAverage;
using nlohmann::json;

namespace {

json summaryJson(const Summary& s) {
    return {{"mean", s.mean}, {"stddev", s.stddev}, {"excess_kurtosis", s.excessKurtosis},
            {"min", s.min}, {"max", s.max}, {"histogram", s.histogram}};
}

// Kolmogorov-Smirnov distance: max |F_a - F_b| of the empirical distributions.
double ksDistance(std::vector<double> a, std::vector<double> b) {
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    size_t i = 0, j = 0;
    double d = 0;
    while (i < a.size() && j < b.size()) {
        const double x = std::min(a[i], b[j]);
        while (i < a.size() && a[i] <= x) ++i;
        while (j < b.size() && b[j] <= x) ++j;
        d = std::max(d, std::fabs(double(i) / a.size() - double(j) / b.size()));
    }
    return d;
}

double rms(const std::vector<double>& a, const std::vector<double>& b) {
    double sq = 0;
    for (size_t i = 0; i < a.size(); ++i) sq += (a[i] - b[i]) * (a[i] - b[i]);
    return std::sqrt(sq / a.size());
}

// Figures 6 and 11: correlation between lattice values of neighbouring lattice points (i, i+1
// along one axis, the three axes pooled) and of points sharing two coordinates (i and i + d,
// d a fixed odd stride); over the whole 2^b_i cube. f(i, j, k) the lattice function.
template <class F>
json latticeCorrelation(int cells, F f) {
    std::vector<double> a, b, c, d, all;
    const int stride = std::max(1, cells / 2 - 1) | 1;
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j)
            for (int k = 0; k < cells; ++k) {
                const double v = f(i, j, k);
                all.push_back(v);
                for (int ax = 0; ax < 3; ++ax) {
                    const int n1[3] = {(i + (ax == 0)) % cells, (j + (ax == 1)) % cells, (k + (ax == 2)) % cells};
                    const int n2[3] = {(i + stride * (ax == 0)) % cells, (j + stride * (ax == 1)) % cells,
                                       (k + stride * (ax == 2)) % cells};
                    a.push_back(v), b.push_back(f(n1[0], n1[1], n1[2]));
                    c.push_back(v), d.push_back(f(n2[0], n2[1], n2[2]));
                }
            }
    const Summary s = summarize(all, 0.0, 1.0, 16);
    return {{"neighbour", correlation(a, b)}, {"shared_two_coords", correlation(c, d)},
            {"stddev", s.stddev}, {"excess_kurtosis", s.excessKurtosis}};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Measurements of the multipass noise (Hart 2001) for docs/MULTIPASS.md"};
    std::string out;
    int size = 256, frames = 5;
    bool quick = false;
    uint32_t seed = 1;
    app.add_option("--out", out, "JSON record (docs/data/multipass.json)")->required();
    app.add_option("--size", size, "quality sample: size x size random coordinates")->check(CLI::Range(16, 1024));
    app.add_option("--frames", frames, "timed frames per configuration (min of N reported)")->check(CLI::Range(1, 100));
    app.add_option("--seed", seed, "tables' and coordinates' seed");
    std::vector<int> sizes{256, 1024};
    app.add_option("--sizes", sizes, "proposals: image sizes");
    app.add_flag("--quick", quick, "b_f 2, 4, 6 only and smaller samples (a smoke run)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    if (quick) size = std::min(size, 64);
    json j;
    int differing = 0;
    try {
        pst::gpu::EglContext ctx;
        j["renderer"] = ctx.renderer();
        j["gl_version"] = ctx.version();
        j["seed"] = seed;
        j["load_average_1min_start"] = loadAverage();

        // ---- quality ----
        std::mt19937 gen(seed);
        Image8 s{size, size, {}}, t = s, r = s;
        for (Image8* im : {&s, &t, &r})
            for (int i = 0; i < size * size; ++i) im->px.push_back(uint8_t(gen() & 255));
        pst::gpu::GlMultipass gl(size, size);
        pst::Profile chip = pst::loadNamedProfile("balanced", pst::sourceDir());
        chip.noiseInterp = pst::NoiseInterp::Linear;
        chip.noiseCorner = pst::NoiseCorner::Value;
        chip.noise = pst::hardwareNoise(chip);
        pst::NoiseOptions ro;
        ro.interp = pst::NoiseInterp::Linear;
        ro.corner = pst::NoiseCorner::Value;
        json q = json::array();
        std::vector<int> bfs = quick ? std::vector<int>{2, 4, 6} : std::vector<int>{1, 2, 3, 4, 5, 6, 7};
        struct Config {
            Variant variant;
            Interp interp;
            const char* name;
        };
        for (const Config& cfg : {Config{Variant::Sgi, Interp::Linear, "sgi"}, Config{Variant::Sgi, Interp::Scurve, "sgi_scurve"},
                                  Config{Variant::Rc, Interp::Linear, "rc"}})
            for (int bf : bfs) {
                Params p;
                p.variant = cfg.variant;
                p.interp = cfg.interp;
                p.format.bf = bf;
                p.seed = seed;
                const Program prog = makeProgram(p);
                const Tables tables = makeTables(p);
                const RcConstants rcc = rcConstants(p);
                const Image8 g = gl.run(prog, tables, s, t, r, pst::gpu::BlendArith::Shader);
                const Image8 cpu = runCpu(prog, tables, s, t, r);
                int diff = 0;
                for (size_t i = 0; i < g.px.size(); ++i) diff += g.px[i] != cpu.px[i];
                differing += diff;
                std::vector<double> noise, ideal, ray, fx;
                ro.interp = cfg.interp == Interp::Scurve ? pst::NoiseInterp::Scurve : pst::NoiseInterp::Linear;
                chip.noiseInterp = ro.interp;
                chip.noise = pst::hardwareNoise(chip);
                for (size_t i = 0; i < g.px.size(); ++i) {
                    const int c[3] = {int(s.px[i]), int(t.px[i]), int(r.px[i])};
                    noise.push_back(g.px[i] / 255.0);
                    ideal.push_back(idealNoise(p, tables, rcc, c[0], c[1], c[2]));
                    // Rayshade and the chip at the same point (lattice units: the byte / 2^b_f)
                    ray.push_back(pst::noise(glm::dvec3(c[0], c[1], c[2]) / double(1 << bf), ro) + 0.5);
                    int lat[3];
                    int64_t frac[3], n, grad[3];
                    for (int a = 0; a < 3; ++a) {
                        lat[a] = ((c[a] >> bf) + 1000000) % 4096;  // after Rayshade's 1e6 offset
                        frac[a] = int64_t(c[a] & ((1 << bf) - 1)) << (chip.noiseLatticeFrac - bf);
                    }
                    pst::noiseFx(chip, lat, frac, &n, grad);
                    fx.push_back(std::ldexp(double(n), -chip.noiseOutFrac) + 0.5);
                }
                json e;
                e["variant"] = cfg.name;
                e["b"] = p.format.b;
                e["b_f"] = bf;
                e["draws"] = prog.draws();
                e["gl_pixels_differing_from_cpu_model"] = diff;
                e["samples"] = noise.size();
                e["rms_vs_ideal_lsb"] = rms(noise, ideal) * 255;
                double mx = 0;
                for (size_t i = 0; i < noise.size(); ++i) mx = std::max(mx, std::fabs(noise[i] - ideal[i]));
                e["max_vs_ideal_lsb"] = mx * 255;
                e["noise"] = summaryJson(summarize(noise, 0, 1, 16));
                e["rayshade"] = summaryJson(summarize(ray, 0, 1, 16));
                e["chip"] = summaryJson(summarize(fx, 0, 1, 16));
                e["ks_vs_rayshade"] = ksDistance(noise, ray);
                e["ks_chip_vs_rayshade"] = ksDistance(fx, ray);
                e["rms_pointwise_vs_rayshade"] = rms(noise, ray);  // different random fields
                e["rms_chip_vs_rayshade"] = rms(fx, ray);          // the same field: fixed-point error
                // Figures 6 / 11: the lattice before and after the final randomization.
                const int cells = 1 << p.format.bi();
                const Tables& T = tables;
                if (cfg.variant == Variant::Sgi)
                    e["lattice_before_final"] = latticeCorrelation(cells, [&](int i, int jj, int k) {
                        return (T[Sran][i] + T[Tran][jj] + T[Rran][k]) / 255.0;
                    });
                else
                    e["lattice_before_final"] = latticeCorrelation(cells, [&](int i, int jj, int k) {
                        return rcFirstStage(p, rcc, i, jj, k) / 255.0;
                    });
                e["lattice"] = latticeCorrelation(cells, [&](int i, int jj, int k) {
                    return latticeValue(p, T, rcc, i, jj, k) / 255.0;
                });
                e["lattice_rayshade"] = latticeCorrelation(cells, [&](int i, int jj, int k) {
                    const int m = pst::noiseHash(i + 1000000, jj + 1000000, k + 1000000, pst::NoiseHash::Rayshade);
                    return 0.5 * pst::NoiseTables::get().value[m] + 0.5;  // Value corner 0.5 R, shifted
                });
                std::fprintf(stderr, "quality %s b_f %d: %d draws, %d differ, rms vs ideal %.2f LSB\n", cfg.name, bf,
                             prog.draws(), diff, rms(noise, ideal) * 255);
                q.push_back(e);
            }
        j["quality"] = q;
        j["quality_samples"] = size * size;
        j["load_average_1min_end"] = loadAverage();

        // ---- proposals ----
        json pr;
        pr["load_average_1min_start"] = loadAverage();
        pr["frames"] = frames;
        json rows = json::array();
        pst::NoiseOptions rp;
        rp.interp = pst::NoiseInterp::Linear;
        rp.corner = pst::NoiseCorner::Value;
        rp.hash = pst::NoiseHash::Perm256;
        for (int n : quick ? std::vector<int>{64} : sizes) {
            std::mt19937 g2(seed + n);
            Image8 ps{n, n, {}}, pt = ps, pr3 = ps;
            for (Image8* im : {&ps, &pt, &pr3})
                for (int i = 0; i < n * n; ++i) im->px.push_back(uint8_t(g2() & 255));
            pst::gpu::GlMultipass gln(n, n);
            auto quality = [&](json& row, const Image8& g, const Params& p, bool rayshade) {
                const Tables tables = makeTables(p);
                const RcConstants rcc = rcConstants(p);
                double sq = 0, sqr = 0;
                for (size_t i = 0; i < g.px.size(); ++i) {
                    const int c[3] = {int(ps.px[i]), int(pt.px[i]), int(pr3.px[i])};
                    const double e = g.px[i] / 255.0 - idealNoise(p, tables, rcc, c[0], c[1], c[2]);
                    sq += e * e;
                    if (rayshade) {
                        const double er = g.px[i] / 255.0 -
                                          (pst::noise(glm::dvec3(c[0], c[1], c[2]) / double(1 << p.format.bf), rp) + 0.5);
                        sqr += er * er;
                    }
                }
                row["rms_vs_ideal_lsb"] = std::sqrt(sq / g.px.size()) * 255;
                row["rms_vs_rayshade_lsb"] = rayshade ? json(std::sqrt(sqr / g.px.size()) * 255) : json(nullptr);
            };
            struct Cfg {
                Variant v;
                bool copy;
                const char* name;
            };
            for (const Cfg& cfg : {Cfg{Variant::Sgi, false, "SGI (4), render to texture"},
                                   Cfg{Variant::Sgi, true, "SGI (4), glCopyTexSubImage2D per draw"},
                                   Cfg{Variant::Rc, false, "register combiners (5), render to texture"},
                                   Cfg{Variant::Rc, true, "register combiners (5), glCopyTexSubImage2D per draw"},
                                   Cfg{Variant::Xor, false, "exclusive-or hash (6.3), render to texture"},
                                   Cfg{Variant::Xor, true, "exclusive-or hash (6.3), glCopyTexSubImage2D per draw"}}) {
                Params p;
                p.variant = cfg.v;
                p.seed = seed;
                const Program prog = makeProgram(p);
                const Tables tables = makeTables(p);
                gln.setCopyTexSubImage(cfg.copy);
                const int fr = n > 256 ? std::max(1, frames / 2) : frames;
                gln.run(prog, tables, ps, pt, pr3, pst::gpu::BlendArith::Shader);  // warm-up
                pst::gpu::Timing tm;
                const Image8 g = gln.run(prog, tables, ps, pt, pr3, pst::gpu::BlendArith::Shader, fr, &tm);
                const Image8 cpu = runCpu(prog, tables, ps, pt, pr3);
                int diff = 0;
                for (size_t i = 0; i < g.px.size(); ++i) diff += g.px[i] != cpu.px[i];
                differing += diff;
                json row{{"name", cfg.name}, {"target", "RGBA8"}, {"size", n}, {"b_f", p.format.bf},
                         {"draws", tm.draws}, {"frames", fr}, {"ms_min", tm.msPerFrameMin},
                         {"ms_mean", tm.msPerFrame}, {"ms_per_draw", tm.msPerFrameMin / tm.draws},
                         {"gl_pixels_differing", diff}};
                quality(row, g, p, cfg.v == Variant::Xor);
                std::fprintf(stderr, "proposals %s %d: %d draws, min %.1f ms\n", cfg.name, n, tm.draws, tm.msPerFrameMin);
                rows.push_back(row);
            }
            gln.setCopyTexSubImage(false);
            {
                // 6.2 in isolation: one copy vs one draw (min over repetitions)
                const int count = n > 256 ? 10 : 50;
                gln.copyMs(count, 1), gln.drawMs(count, 1);  // warm-up
                const double c = gln.copyMs(count, frames), d = gln.drawMs(count, frames);
                pr["isolated"].push_back({{"size", n}, {"copy_ms", c}, {"draw_ms", d}, {"count", count}, {"reps", frames}});
                std::fprintf(stderr, "isolated %d: copy %.3f ms, draw %.3f ms\n", n, c, d);
            }
            {
                Params p;
                p.variant = Variant::Xor;
                pst::gpu::Timing tm;
                pst::gpu::singlePassNoise(ps, pt, pr3, p, 1);  // warm-up (compiles the shader)
                const Image8 g = pst::gpu::singlePassNoise(ps, pt, pr3, p, frames, &tm);
                json row{{"name", "single-pass fragment shader (the exclusive-or variant's noise, float)"},
                         {"target", "RGBA8"}, {"size", n}, {"b_f", p.format.bf}, {"draws", 1}, {"frames", frames},
                         {"ms_min", tm.msPerFrameMin}, {"ms_mean", tm.msPerFrame}, {"ms_per_draw", tm.msPerFrameMin},
                         {"gl_pixels_differing", nullptr}};
                quality(row, g, p, true);
                std::fprintf(stderr, "proposals single pass %d: min %.2f ms\n", n, tm.msPerFrameMin);
                rows.push_back(row);
            }
        }
        // Section 6.1: the exclusive-or variant at b = 8, 10, 16 on GL and 24 (the packed 24-bit
        // luminance: L = R << 16 | G << 8 | B inside a combiner of 16.8 fixed point, modelled as
        // 24-bit UNORM images; no GL target) with b_i = 4 (16 cells, the paper's Figure 4) and
        // b_f = b - 4; errors in units of 1/255 for comparison across b.
        {
            const int n = quick ? 64 : 256;
            struct Prec {
                int b;
                const char* target;
                bool gl;
                pst::gpu::TargetFormat fmt;
            };
            for (const Prec& pc : {Prec{8, "RGBA8", true, pst::gpu::TargetFormat::RGBA8},
                                   Prec{10, "RGB10_A2", true, pst::gpu::TargetFormat::RGB10A2},
                                   Prec{16, "R16_EXT", true, pst::gpu::TargetFormat::R16},
                                   Prec{24, "packed 24-bit luminance (CPU model)", false, pst::gpu::TargetFormat::RGBA8}}) {
                Params p;
                p.variant = Variant::Xor;
                p.format.b = pc.b;
                p.format.bf = pc.b - 4;
                const uint32_t M = uint32_t(p.format.max());
                std::mt19937 g3(seed + 7);
                Image8 ps{n, n, {}}, pt = ps, pr3 = ps;
                for (Image8* im : {&ps, &pt, &pr3})
                    for (int i = 0; i < n * n; ++i) im->px.push_back(g3() & M);
                const Program prog = xorProgram(p);
                const Tables tables = makeTables(p);
                Stats stats;
                const Image8 cpu = runCpu(prog, tables, ps, pt, pr3, &stats);
                Image8 g = cpu;
                json row{{"name", std::string("exclusive-or hash (6.3), b = ") + std::to_string(pc.b) + ", b_i 4"},
                         {"target", pc.target}, {"size", n}, {"b", pc.b}, {"b_f", p.format.bf}, {"draws", prog.draws()},
                         {"min_tie_margin_lsb", stats.minTieMargin}};
                if (pc.gl) {
                    pst::gpu::GlMultipass glp(n, n, pc.fmt);
                    glp.run(prog, tables, ps, pt, pr3, pst::gpu::BlendArith::Shader);
                    pst::gpu::Timing tm;
                    g = glp.run(prog, tables, ps, pt, pr3, pst::gpu::BlendArith::Shader, frames, &tm);
                    int diff = 0, maxd = 0;
                    for (size_t i = 0; i < g.px.size(); ++i) {
                        diff += g.px[i] != cpu.px[i];
                        maxd = std::max<int>(maxd, std::abs(int64_t(g.px[i]) - int64_t(cpu.px[i])));
                    }
                    row["frames"] = frames;
                    row["ms_min"] = tm.msPerFrameMin;
                    row["ms_mean"] = tm.msPerFrame;
                    row["ms_per_draw"] = tm.msPerFrameMin / tm.draws;
                    row["gl_pixels_differing"] = diff;
                    row["gl_max_difference_lsb_of_b"] = maxd;
                } else {
                    row["ms_min"] = nullptr;
                    row["ms_per_draw"] = nullptr;
                    row["gl_pixels_differing"] = nullptr;
                }
                const RcConstants rcc = rcConstants(p);
                double sq = 0, sqr = 0;
                for (size_t i = 0; i < g.px.size(); ++i) {
                    const uint32_t c[3] = {ps.px[i], pt.px[i], pr3.px[i]};
                    const double v = g.px[i] / double(M);
                    const double e = v - idealNoise(p, tables, rcc, int(c[0]), int(c[1]), int(c[2]));
                    const double er = v - (pst::noise(glm::dvec3(c[0], c[1], c[2]) / double(1 << p.format.bf), rp) + 0.5);
                    sq += e * e, sqr += er * er;
                }
                row["rms_vs_ideal_lsb"] = std::sqrt(sq / g.px.size()) * 255;
                row["rms_vs_rayshade_lsb"] = std::sqrt(sqr / g.px.size()) * 255;
                std::fprintf(stderr, "precision b %d: rms vs Rayshade %.4f (1/255)\n", pc.b, std::sqrt(sqr / g.px.size()) * 255);
                rows.push_back(row);
            }
        }
        pr["rows"] = rows;
        pr["load_average_1min_end"] = loadAverage();
        pr["notes"] = json::array();
        j["proposals"] = pr;
    } catch (const pst::gpu::EglUnavailable& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
    std::ofstream o(out);
    o << j.dump(1) << "\n";
    if (!o) {
        std::cerr << "error: cannot write " << out << "\n";
        return 2;
    }
    return differing ? 1 : 0;
}
