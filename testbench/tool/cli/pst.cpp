// pst: the project's one command-line tool.
//   pst render SCENE      filtered, unfiltered, filter-width (and ground-truth) images + report
//   pst eval              texture block + fragment file -> f, grad_s f, w, filtered RGBA
//   pst fragments SCENE   the rasterizer's fragment stream as a fragment file
//   pst compare A B       RMS / PSNR between two images
//   pst render SCENE --profile P   the same scene through the RTL (and golden) model of profile P
//   pst regress           every scene x every profile through the RTL; non-zero exit on any mismatch
//   pst animate SCENE     the scene's time track: frames, videos, flicker against the ground truth
//   pst atlas SCENE       texture-atlas mode: the atlas filled by the models, the object texture-mapped
// Exit status: 0 success, 1 failure (including RTL mismatches), 2 bad input or usage.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <iostream>
#include <map>
#include <sstream>

#include <CLI/CLI.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "animate.h"
#include "atlas_fill.h"
#include "atlas_render.h"
#include "multires.h"
#include "driver.h"
#include "fixed.h"
#include "fragments.h"
#include "hwrender.h"
#include "imageio.h"
#include "junit.h"
#include "random_regress.h"
#include "render.h"
#include "scene.h"
#include "source_dir.h"

namespace fs = std::filesystem;
using namespace pst;

namespace {

struct RenderArgs {
    std::string scene, outDir;
    int size = 0, width = 0, height = 0, truth = 0, threads = 0;
    uint64_t seed = 1;
    bool quiet = false;
    std::string bandlimit;    // every texture's bandlimit (parseBandlimit's names)
    std::string filter;       // every texture's filter kind (parseFilterKind's names)
    std::vector<std::string> variants;  // extra filtered images (parseVariant's spellings)
};

std::vector<FilterVariant> parseVariants(const std::vector<std::string>& specs) {
    std::vector<FilterVariant> out;
    for (const auto& s : specs) {
        FilterVariant v;
        std::string why;
        if (!parseVariant(s, &v, &why)) throw InputError("--variants: " + why);
        for (const auto& o : out)
            if (o.name == v.name) throw InputError("--variants: '" + s + "' given twice");
        out.push_back(v);
    }
    return out;
}

// --bandlimit and --filter: every texture of the scene gets them (a bandlimit a texture cannot
// take is refused).
void overrideTextures(Scene& scene, const std::string& bandlimit, const std::string& filter) {
    for (auto& t : scene.textures) {
        if (!bandlimit.empty()) {
            parseBandlimit(bandlimit, &t.bandlimit);
            t.bandlimitSource.clear();   // the value is the option's, not the scene line's
            if (std::string why = bandlimitUnsupported(t, t.bandlimit); !why.empty())
                throw InputError("--bandlimit: " + bandlimit + ": texture '" + t.name + "': " + why);
        }
        if (!filter.empty()) parseFilterKind(filter, &t.filter);
    }
}

// Every variant's bandlimit must suit every texture of the scene.
void checkVariants(const Scene& scene, const std::vector<FilterVariant>& variants) {
    for (const auto& v : variants)
        for (const auto& t : scene.textures)
            if (std::string why = bandlimitUnsupported(t, v.bandlimit); !why.empty())
                throw InputError("--variants: " + v.name + ": texture '" + t.name + "': " + why);
}

// Progress on stderr: one rewritten line on a terminal, a line per phase otherwise.
std::function<void(const std::string&, double)> progressPrinter(const std::string& name, bool quiet) {
    if (quiet) return {};
    const bool tty = isatty(STDERR_FILENO);
    return [name, tty, last = std::string()](const std::string& phase, double frac) mutable {
        if (tty) {
            std::fprintf(stderr, "\r%s: %-6s %5.1f%%", name.c_str(), phase.c_str(), 100.0 * frac);
            if (frac >= 1.0) std::fprintf(stderr, "\n");
        } else if (frac >= 1.0 || phase != last) {
            if (frac >= 1.0) std::fprintf(stderr, "%s: %s done\n", name.c_str(), phase.c_str());
        }
        last = phase;
    };
}

// Hardware-model options shared by render --profile, regress and eval --model.
struct HwArgs {
    std::vector<std::string> profiles;
    std::string model = "rtl";      // rtl | golden
    SimOptions sim;
    std::string trace;
    std::string html;               // render --profile --html: the runs' page
};

extern "C" char** environ;

// The HTML page of hardware runs (table, image viewer per scene) is written by
// scripts/report.py, the one source of the report's pages. Returns 0, or 1 when it fails.
int writeHtmlPage(const std::string& page, std::vector<std::string> args) {
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    args.insert(args.begin(), {python, sourceDir() + "/scripts/report.py", "--html", page});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid;
    int status = 0;
    if (posix_spawnp(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ) != 0 ||
        waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::cerr << "error: --html: " << args[1] << " did not write " << page << "\n";
        return 1;
    }
    std::cout << "page: " << page << "\n";
    return 0;
}

// A verilated profile by its name (rtl/configs or PST_EXTRA_PROFILE_DIR), else a name in
// rtl/configs or a profile file. For the RTL (rtl = true) the profile must have a verilated
// model in this build, and the same values as the file that model was built from: a copy of
// full.toml with other widths, named full.toml, is refused, not run against the full RTL.
Profile profileByName(const std::string& name, bool rtl = false) {
    const std::string built = isProfileFile(name) ? "" : rtlProfilePath(name);
    Profile p = built.empty() ? loadNamedProfile(name, sourceDir()) : loadProfile(built);
    if (!rtl) return p;
    const std::string verilated = rtlProfilePath(p.name);
    if (verilated.empty()) {
        std::string list;
        for (const auto& n : rtlProfiles()) list += (list.empty() ? "" : ", ") + n;
        throw InputError(p.path + ": profile '" + p.name + "' has no verilated model in this build (verilated: " + list +
                         "; add it with -DPST_PROFILES or -DPST_EXTRA_PROFILE_DIR, or use --model golden)");
    }
    const Profile v = loadProfile(verilated);
    if (std::string key = profileDifference(p, v); !key.empty())
        throw InputError(p.path + ": " + key + ": differs from the profile the '" + p.name + "' RTL was verilated from (" +
                         verilated + "); rename the profile or verilate it (-DPST_EXTRA_PROFILE_DIR)");
    return p;
}

// The files one command writes: if a later write fails (a full disk), the ones written so far
// are removed again, and the folder if this command created it, so no half output is left.
class OutputFiles {
public:
    explicit OutputFiles(const fs::path& dir) : dir_(dir), created_(!fs::exists(dir)) { fs::create_directories(dir); }
    std::string operator()(const std::string& name) {
        const fs::path f = dir_ / name;
        if (!fs::exists(f)) files_.push_back(f);   // never remove what was there before
        return f.string();
    }
    void keep() { keep_ = true; }
    ~OutputFiles() {
        if (keep_) return;
        std::error_code ec;
        for (const auto& f : files_) fs::remove(f, ec);
        if (created_) fs::remove(dir_, ec);   // only if empty
    }

private:
    fs::path dir_;
    bool created_;
    bool keep_ = false;
    std::vector<fs::path> files_;
};

// Fails (InputError) unless a trace file can be written: its folder exists.
void checkTracePath(const std::string& trace) {
    const fs::path dir = fs::path(trace).parent_path();
    if (!dir.empty() && !fs::is_directory(dir))
        throw InputError("--trace: folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(trace)) throw InputError("--trace: '" + trace + "' is a folder, not a file");
}

// Whether this build verilated `profile` with its assertions (the checked flavour).
bool asserted(const std::string& profile) {
    const std::vector<std::string> a = rtlAssertedProfiles();
    return std::find(a.begin(), a.end(), profile) != a.end();
}

nlohmann::json hwJson(const std::string& scene, const Profile& p, const std::string& model,
                      const HwRenderResult& r, int w, int h) {
    nlohmann::json j;
    j["scene"] = scene;
    j["profile"] = p.name;
    j["model"] = model;
    j["width"] = w;
    j["height"] = h;
    j["fragments"] = r.fragments;
    j["passed"] = r.passed;
    j["mismatches"] = r.mismatches;
    j["pixels_checked"] = r.pixels;
    j["cycles"] = r.cycles;
    j["cycles_per_pixel"] = r.cyclesPerPixel;
    j["assertions_verilated"] = asserted(p.name);
    j["seconds"] = {{"rtl", r.rtlSeconds}, {"golden", r.goldenSeconds}, {"reference", r.referenceSeconds}};
    auto rate = [&](double sec) { return sec > 0 ? double(r.fragments) / sec : 0.0; };
    j["pixels_per_second"] = {{"rtl", rate(r.rtlSeconds)}, {"golden", rate(r.goldenSeconds)},
                              {"reference", rate(r.referenceSeconds)}};
    j["vs_reference"] = {{"max_lsb", r.vsReference.maxLsb}, {"rms", r.vsReference.rms},
                         {"psnr", r.vsReference.psnr}, {"within_1lsb_percent", r.vsReference.within1Lsb}};
    j["notes"] = r.notes;
    if (r.vsTruth.psnr != 0 || r.vsTruth.rms != 0) {
        j["vs_truth"] = {{"max_lsb", r.vsTruth.maxLsb}, {"rms", r.vsTruth.rms}, {"psnr", r.vsTruth.psnr},
                         {"within_1lsb_percent", r.vsTruth.within1Lsb}};
        j["reference_vs_truth"] = {{"rms", r.referenceVsTruth.rms}, {"psnr", r.referenceVsTruth.psnr}};
    }
    return j;
}

// The first texture of the scene's objects that profile p cannot run (hardwareUnsupported), or "".
std::string unsupportedTexture(const Scene& scene, const Profile& p) {
    for (const auto& o : scene.objects)
        if (std::string why = hardwareUnsupported(p, scene.textures[o.texture]); !why.empty()) return why;
    return "";
}

int runHardwareRender(const RenderArgs& a, const HwArgs& hw) {
    const int w = a.size ? a.size : a.width, h = a.size ? a.size : a.height;
    Scene scene = loadScene(a.scene, w, h);
    overrideTextures(scene, a.bandlimit, a.filter);
    const std::string stem = fs::path(a.scene).stem().string();
    int rc = 0;
    std::vector<std::string> pageArgs;
    // Every profile is loaded and checked before anything is written (a bad second profile
    // must not leave the first one's images behind).
    std::vector<Profile> profiles;
    for (const std::string& name : hw.profiles) {
        profiles.push_back(profileByName(name, hw.model == "rtl"));
        if (std::string why = unsupportedTexture(scene, profiles.back()); !why.empty()) throw InputError(why);
    }
    if (!hw.trace.empty()) checkTracePath(hw.trace);
    for (const Profile& p : profiles) {
        const fs::path dir = a.outDir.empty() ? fs::path("out") / stem / p.name
                                              : (hw.profiles.size() > 1 ? fs::path(a.outDir) / p.name : fs::path(a.outDir));
        std::unique_ptr<RtlModel> rtl;
        if (hw.model == "rtl") {
            SimOptions so = hw.sim;
            if (!hw.trace.empty()) so.traceFile = hw.trace;
            rtl = makeRtlModel(p.name, so);
        }
        HwRenderOptions ho;
        ho.progress = progressPrinter(stem + "/" + p.name, a.quiet);
        ho.truthSamples = a.truth;
        HwRenderResult r = renderHardware(scene, p, rtl.get(), ho);
        OutputFiles out(dir);
        writeImage(r.hardware, out(hw.model + ".png"));
        writeImage(r.reference, out("reference.png"));
        writeImage(r.difference, out("difference.png"));
        writeTextFile(out("summary.json"),
                      hwJson(a.scene, p, hw.model, r, scene.camera.width, scene.camera.height).dump(2) + "\n");
        out.keep();
        pageArgs.insert(pageArgs.end(), {"--summary", (dir / "summary.json").string()});
        std::cout << stem << " [" << p.name << ", " << hw.model << "]: " << r.fragments << " fragments";
        if (rtl) std::cout << ", " << r.mismatches << " mismatches, " << r.cyclesPerPixel << " cycles/pixel";
        std::cout << ", PSNR vs reference " << r.vsReference.psnr << " dB, " << r.vsReference.within1Lsb
                  << "% within 1 LSB -> " << dir.string() << "\n";
        for (const auto& n : r.notes) std::cout << "  note: " << n << "\n";
        if (rtl && !r.passed) {
            std::cout << r.scoreboard;
            rc = 1;
        }
    }
    if (!hw.html.empty()) rc = std::max(rc, writeHtmlPage(hw.html, pageArgs));
    return rc;
}

// The command that runs one scene x profile of a regression again, with the same inputs, gaps and stalls.
std::string regressReplay(const std::string& scene, int size, const std::string& profile, const SimOptions& so) {
    std::ostringstream os;
    os << "pst regress " << scene << " --size " << size << " --profile " << profile;
    if (so.seed != SimOptions{}.seed) os << " --sim-seed " << so.seed;
    if (so.inputGapRate > 0) os << " --gap-rate " << so.inputGapRate;
    if (so.outputStallRate > 0) os << " --stall-rate " << so.outputStallRate;
    if (so.timeoutCycles) os << " --timeout " << so.timeoutCycles;
    if (so.busyWriteAfter) os << " --inject-assert " << so.busyWriteAfter - 1;
    return os.str();
}

int runRegress(const std::vector<std::string>& scenes, int size, const HwArgs& hw, const std::string& outPath,
               const std::string& imageDir, const std::string& junitPath) {
    nlohmann::json all = nlohmann::json::array();
    std::vector<JunitCase> cases;
    int failures = 0, skipped = 0;
    // Every scene and profile is loaded and checked before the first run writes anything.
    std::vector<Scene> loaded;
    for (const std::string& path : scenes) loaded.push_back(loadScene(path, size, size));
    std::vector<Profile> profiles;
    for (const std::string& name : hw.profiles) profiles.push_back(profileByName(name, true));
    std::printf("%-14s %-8s %9s %10s %8s %9s %10s %12s\n", "scene", "profile", "pixels", "mismatch", "PSNR",
                "<=1LSB%", "cyc/pixel", "rtl px/s");
    for (size_t si = 0; si < scenes.size(); ++si) {
        const std::string& path = scenes[si];
        const Scene& scene = loaded[si];
        const std::string stem = fs::path(path).stem().string();
        for (const Profile& p : profiles) {
            // A scene the profile cannot run (a reference-only noise basis) is skipped, visibly,
            // and kept out of the JSON: it neither passes nor fails.
            if (std::string why = unsupportedTexture(scene, p); !why.empty()) {
                std::printf("%-14s %-8s SKIPPED: %s\n", stem.c_str(), p.name.c_str(), why.c_str());
                std::fflush(stdout);
                ++skipped;
                cases.push_back({"regress." + p.name, stem, 0, false, why, "", true});
                continue;
            }
            auto rtl = makeRtlModel(p.name, hw.sim);
            HwRenderOptions ho;
            // A profile with the fade unit runs every scene with the hardware's bandlimited
            // octaves on (its textures' bandlimit = "isotropic"; the reference renders the same).
            Scene faded;
            if (p.bandlimit()) {
                faded = scene;
                for (Texture& t : faded.textures)
                    if (t.bandlimit == Bandlimit::Off) t.bandlimit = Bandlimit::Isotropic;
            }
            HwRenderResult r;
            try {
                r = renderHardware(p.bandlimit() ? faded : scene, p, rtl.get(), ho);
            } catch (const RtlAssertionError& e) {
                // A failed run like a mismatch: recorded, the next run goes on.
                const std::string replay = regressReplay(path, size, p.name, hw.sim);
                std::printf("%-14s %-8s ASSERTION at cycle %llu\n", stem.c_str(), p.name.c_str(),
                            (unsigned long long)e.cycle);
                std::cout << e.what() << "\nreplay alone: " << replay << "\n";
                std::fflush(stdout);
                ++failures;
                cases.push_back({"regress." + p.name, stem, 0, true, "RTL assertion at cycle " + std::to_string(e.cycle),
                                 std::string(e.what()) + "\nreplay alone: " + replay + "\n"});
                HwRenderResult none;   // the same keys as a finished run's, zero
                none.passed = false;
                nlohmann::json j = hwJson(path, p, "rtl", none, scene.camera.width, scene.camera.height);
                j["assertion"] = {{"cycle", e.cycle}, {"pixels_out", e.pixelsOut}};
                j["replay"] = replay;
                all.push_back(j);
                continue;
            }
            std::printf("%-14s %-8s %9lld %10zu %8.2f %9.2f %10.3f %12.0f\n", stem.c_str(), p.name.c_str(),
                        r.fragments, r.mismatches, r.vsReference.psnr, r.vsReference.within1Lsb, r.cyclesPerPixel,
                        r.rtlSeconds > 0 ? double(r.fragments) / r.rtlSeconds : 0.0);
            std::fflush(stdout);
            if (!r.passed) {
                ++failures;
                std::cout << r.scoreboard;
            }
            cases.push_back({"regress." + p.name, stem, r.rtlSeconds + r.goldenSeconds + r.referenceSeconds, !r.passed,
                             std::to_string(r.mismatches) + " mismatches", r.scoreboard});
            all.push_back(hwJson(path, p, "rtl", r, scene.camera.width, scene.camera.height));
            if (!r.passed) all.back()["replay"] = regressReplay(path, size, p.name, hw.sim);
            if (!imageDir.empty()) {
                const fs::path dir = fs::path(imageDir) / stem / p.name;
                fs::create_directories(dir);
                writeImage(r.hardware, (dir / "rtl.png").string());
                writeImage(r.reference, (dir / "reference.png").string());
                writeImage(r.difference, (dir / "difference.png").string());
            }
        }
    }
    if (!outPath.empty()) writeTextFile(outPath, all.dump(2) + "\n");
    if (!junitPath.empty()) writeJunit(junitPath, "pst regress", cases);
    std::printf("%s: %zu runs, %d failed", failures ? "FAILED" : "PASSED", all.size(), failures);
    if (skipped) std::printf(", %d skipped (no hardware unit for their noise basis)", skipped);
    std::printf("\n");
    return failures ? 1 : 0;
}

// pst regress --random N: constrained-random textures and fragments (testbench/verify/random).
int runRandom(const HwArgs& hw, RandomRegressOptions o, bool quiet, const std::string& outPath,
              const std::string& junitPath) {
    int failures = 0;
    std::vector<JunitCase> cases;
    nlohmann::json all = nlohmann::json::array();
    std::printf("%-14s %10s %9s %9s %10s %10s %12s\n", "profile", "fragments", "textures", "mismatch", "cyc/pixel",
                "seconds", "fragments/s");
    std::vector<Profile> profiles;
    for (const std::string& name : hw.profiles) profiles.push_back(profileByName(name, true));
    for (const Profile& p : profiles) {
        const std::string& name = p.name;
        if (!quiet && isatty(STDERR_FILENO))
            o.progress = [&](uint64_t done, uint64_t total) {
                std::fprintf(stderr, "\r%s: %llu / %llu", p.name.c_str(), (unsigned long long)done,
                             (unsigned long long)total);
                if (done >= total) std::fprintf(stderr, "\n");
            };
        const RandomRegressResult r = runRandomRegress(p, p.name, o);
        std::printf("%-14s %10llu %9llu %9llu %10.3f %10.1f %12.0f\n", p.name.c_str(),
                    (unsigned long long)r.fragments, (unsigned long long)r.textures, (unsigned long long)r.mismatches,
                    r.fragments ? double(r.cycles) / double(r.fragments) : 0.0, r.seconds,
                    r.seconds > 0 ? double(r.fragments) / r.seconds : 0.0);
        std::fflush(stdout);
        JunitCase jc{"regress.random." + p.name, "seed " + std::to_string(o.seed) + " fragments " +
                     std::to_string(r.firstFragment) + ".." + std::to_string(r.firstFragment + r.fragments),
                     r.seconds, !r.passed, "", ""};
        // The command that replays the first failure alone (the segment holding it, same inputs).
        std::string replay;
        if (r.firstBad != UINT64_MAX) {
            replay = "pst regress --random " + std::to_string(r.replayFragments) + " --seed " + std::to_string(o.seed) +
                     " --from " + std::to_string(r.firstBad) + " --batch " + std::to_string(o.maxBatch) +
                     " --profile " + name + " --probes";
            if (o.injectAssert != UINT64_MAX) replay += " --inject-assert " + std::to_string(o.injectAssert);
        }
        all.push_back({{"profile", p.name},
                       {"seed", o.seed},
                       {"first_fragment", r.firstFragment},
                       {"fragments", r.fragments},
                       {"textures", r.textures},
                       {"mismatches", r.mismatches},
                       {"first_bad", r.firstBad == UINT64_MAX ? nlohmann::json(nullptr) : nlohmann::json(r.firstBad)},
                       {"assertion", r.assertion ? nlohmann::json({{"cycle", r.assertionCycle}}) : nlohmann::json(nullptr)},
                       {"assertions_verilated", asserted(name)},
                       {"replay", replay.empty() ? nlohmann::json(nullptr) : nlohmann::json(replay)},
                       {"cycles_per_pixel", r.fragments ? double(r.cycles) / double(r.fragments) : 0.0},
                       {"cycles", r.cycles},
                       {"seconds", r.seconds},
                       {"rtl_seconds", r.rtlSeconds},
                       {"golden_seconds", r.goldenSeconds},
                       {"passed", r.passed}});
        if (!r.passed) {
            ++failures;
            const std::string what = r.assertion ? "RTL assertion" : "mismatch";
            const std::string at = r.firstBad == UINT64_MAX ? std::string("?") : std::to_string(r.firstBad);
            jc.message = r.assertion ? "RTL assertion at cycle " + std::to_string(r.assertionCycle) + ", fragment " + at
                                     : std::to_string(r.mismatches) + " mismatches, first at fragment " + at;
            jc.output = r.report + (replay.empty() ? "" : "replay alone: " + replay + "\n");
            cases.push_back(jc);
            std::cout << r.report;
            if (!replay.empty())
                std::cout << "first " << what << ": seed " << o.seed << ", fragment " << r.firstBad
                          << "; replay alone: " << replay << "\n";
            if (!asserted(name))
                std::cout << "(" << name << " is verilated here without assertions; a build configured with "
                          << "-DPST_SIM_ASSERT=ON replays it with them)\n";
        } else {
            cases.push_back(jc);
        }
    }
    if (!outPath.empty()) writeTextFile(outPath, all.dump(2) + "\n");
    if (!junitPath.empty()) writeJunit(junitPath, "pst regress --random", cases);
    std::printf("%s: %zu profiles, %d failed (seed %llu)\n", failures ? "FAILED" : "PASSED", hw.profiles.size(),
                failures, (unsigned long long)o.seed);
    return failures ? 1 : 0;
}

int runRender(const RenderArgs& a) {
    const int w = a.size ? a.size : a.width, h = a.size ? a.size : a.height;
    Scene scene = loadScene(a.scene, w, h);
    overrideTextures(scene, a.bandlimit, a.filter);
    const std::string stem = fs::path(a.scene).stem().string();
    const fs::path dir = a.outDir.empty() ? fs::path("out") / stem : fs::path(a.outDir);

    RenderOptions opt;
    opt.truthSamples = a.truth;
    opt.seed = a.seed;
    opt.threads = a.threads;
    opt.progress = progressPrinter(stem, a.quiet);
    opt.variants = parseVariants(a.variants);
    checkVariants(scene, opt.variants);
    const auto t0 = std::chrono::steady_clock::now();
    RenderResult r = render(scene, opt);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    OutputFiles out(dir);
    writeImage(r.filtered, out("filtered.png"));
    writeImage(r.filtered, out("filtered.exr"));
    writeImage(r.unfiltered, out("unfiltered.png"));
    writeImage(r.filterWidth, out("width.png"), Tone::FilterWidth);
    writeImage(r.filterWidth, out("width.exr"), Tone::FilterWidth);

    nlohmann::json j;
    j["scene"] = a.scene;
    j["title"] = scene.title;
    j["filter"] = a.filter;
    j["bandlimit"] = a.bandlimit;
    j["width"] = scene.camera.width;
    j["height"] = scene.camera.height;
    j["fragments"] = r.stats.fragments;
    j["seconds"] = {{"total", seconds}, {"raster", r.stats.rasterSeconds},
                    {"shade", r.stats.shadeSeconds}, {"truth", r.stats.truthSeconds}};
    std::ostringstream line;
    line << stem << ": " << scene.camera.width << "x" << scene.camera.height << ", "
         << r.stats.fragments << " fragments, " << seconds << " s";
    if (a.truth > 0) {
        writeImage(r.truth, out("truth.png"));
        writeImage(r.truth, out("truth.exr"));
        const ImageDiff df = compareRgb(r.filtered, r.truth), du = compareRgb(r.unfiltered, r.truth);
        j["truth_samples"] = a.truth * a.truth;
        j["vs_truth"] = {{"filtered", {{"rms", df.rmsError}, {"psnr", df.psnr}, {"max", df.maxError}}},
                         {"unfiltered", {{"rms", du.rmsError}, {"psnr", du.psnr}, {"max", du.maxError}}}};
        line << ", RMS vs truth: filtered " << df.rmsError << ", unfiltered " << du.rmsError;
    }
    // Variants: every texture's filter and bandlimit replaced (variant_<name>.png).
    for (size_t v = 0; v < opt.variants.size(); ++v) {
        const FilterVariant& fv = opt.variants[v];
        writeImage(r.variants[v], out("variant_" + fv.name + ".png"));
        nlohmann::json e = {{"filter", toString(fv.filter)}, {"bandlimit", toString(fv.bandlimit)}};
        if (a.truth > 0) {
            const ImageDiff d = compareRgb(r.variants[v], r.truth);
            e["vs_truth"] = {{"rms", d.rmsError}, {"psnr", d.psnr}, {"max", d.maxError}};
            line << ", " << fv.name << " " << d.rmsError;
        }
        j["variants"][fv.name] = e;
    }
    writeTextFile(out("report.json"), j.dump(2) + "\n");
    out.keep();
    std::cout << line.str() << " -> " << dir.string() << "\n";
    return 0;
}

int runEval(const std::string& texPath, const std::string& fragPath, const std::string& outPath,
            const std::string& filterName, const std::string& model, const HwArgs& hw) {
    Texture tex = loadTexture(texPath);
    FilterKind kind = tex.filter;
    if (!filterName.empty() && !parseFilterKind(filterName, &kind))
        throw InputError("--filter: unknown filter '" + filterName + "' (expected none, mip, mip_linear, sat, box or trapezoid)");
    const auto frags = loadFragments(fragPath);
    std::ostringstream os;
    if (model != "reference") {
        // The hardware models: same columns, from the fixed-point values.
        if (hw.profiles.size() != 1) throw InputError("--profile: eval takes exactly one profile");
        const Profile p = profileByName(hw.profiles[0], model == "rtl");
        tex.filter = kind;
        TextureProgram prog = programTexture(p, tex);
        std::vector<FragmentFx> in;
        for (size_t i = 0; i < frags.size(); ++i)
            in.push_back(quantizeFragment(p, uint32_t(i), frags[i].s, frags[i].dsdx, frags[i].dsdy));
        GoldenPipeline golden(p);
        for (const auto& [a, d] : prog.writes) golden.write(a, d);
        std::vector<PixelFx> out;
        for (const auto& f : in) out.push_back(golden.eval(f));
        if (model == "rtl") {
            auto rtl = makeRtlModel(p.name, hw.sim);
            rtl->write(prog.writes);
            std::vector<PixelFx> got = rtl->run(in, prog.activeOctaves);
            size_t bad = 0;
            for (size_t i = 0; i < got.size(); ++i) bad += !(got[i] == out[i]);
            if (bad) std::cerr << "warning: rtl differs from golden at " << bad << " of " << got.size() << " fragments\n";
            out = got;
        }
        os << "# f  df/ds df/dt df/dr  w  r g b a   (texture " << texPath << ", profile " << p.name << ", model "
           << model << ", filter code " << prog.filterKind << ")\n";
        char buf[512];
        for (const auto& px : out) {
            const glm::dvec4 c = unpackRgba(p, px.rgba);
            std::snprintf(buf, sizeof buf, "%.17g  %.17g %.17g %.17g  %.17g  %.17g %.17g %.17g %.17g\n",
                          fx::toDouble(px.f, p.f.fracBits), fx::toDouble(px.grad[0], p.grad.fracBits),
                          fx::toDouble(px.grad[1], p.grad.fracBits), fx::toDouble(px.grad[2], p.grad.fracBits),
                          fx::toDouble(px.w, p.widthFrac) / p.clutSize(), c.r, c.g, c.b, c.a);
            os << buf;
        }
        if (outPath.empty() || outPath == "-") std::cout << os.str();
        else writeTextFile(outPath, os.str());
        return 0;
    }
    os << "# f  df/ds df/dt df/dr  w  r g b a   (texture " << texPath << ", filter " << toString(kind) << ")\n";
    char buf[512];
    for (const auto& fr : frags) {
        const TextureSample t = shade(tex, fr.s, fr.dsdx, fr.dsdy, kind);
        std::snprintf(buf, sizeof buf, "%.17g  %.17g %.17g %.17g  %.17g  %.17g %.17g %.17g %.17g\n", t.f,
                      t.gradS.x, t.gradS.y, t.gradS.z, t.filterWidth, t.rgba.r, t.rgba.g, t.rgba.b, t.rgba.a);
        os << buf;
    }
    if (outPath.empty() || outPath == "-") std::cout << os.str();
    else writeTextFile(outPath, os.str());
    return 0;
}

int runFragments(const std::string& scenePath, int size, int layer, const std::string& outPath) {
    Scene scene = loadScene(scenePath, size, size);
    if (layer < 0 || layer >= scene.layers())
        throw InputError("--layer: scene has layers 0.." + std::to_string(scene.layers() - 1));
    std::vector<FragmentRecord> recs;
    for (const auto& f : sceneFragments(scene, layer)) recs.push_back({f.s, f.dsdx, f.dsdy});
    std::ostringstream os;
    writeFragments(os, recs);
    if (outPath.empty() || outPath == "-") std::cout << os.str();
    else writeTextFile(outPath, os.str());
    return 0;
}

// An image for compare: readable, and every pixel finite (NaN would make RMS and PSNR
// meaningless: an image full of NaN compared with itself gave RMS 0).
Image readFiniteImage(const std::string& path) {
    Image img;
    try {
        img = readImage(path);
    } catch (const std::runtime_error& e) {
        throw InputError(e.what());
    }
    for (size_t i = 0; i < img.data.size(); ++i)
        if (!std::isfinite(img.data[i])) {
            const size_t px = i / size_t(img.channels);
            throw InputError(path + ": pixel (" + std::to_string(px % size_t(img.width)) + ", " +
                             std::to_string(px / size_t(img.width)) + "): NaN or infinite value");
        }
    return img;
}

int runCompare(const std::string& a, const std::string& b) {
    const Image A = readFiniteImage(a), B = readFiniteImage(b);
    if (A.width != B.width || A.height != B.height || A.channels < 3 || B.channels < 3)
        throw InputError(b + ": " + std::to_string(B.width) + " x " + std::to_string(B.height) + " x " +
                         std::to_string(B.channels) + " does not match " + a + " (" + std::to_string(A.width) + " x " +
                         std::to_string(A.height) + " x " + std::to_string(A.channels) + "; RGB needed)");
    const ImageDiff d = compareRgb(A, B);
    std::cout << "mean " << d.meanError << "  rms " << d.rmsError << "  max " << d.maxError
              << "  psnr " << d.psnr << " dB\n";
    return 0;
}


// pst atlas: the scene's layer-0 triangles in a meshed atlas (Carr and Hart section 4), filled
// through the reference (and a profile's golden model and RTL, scoreboarded), the view drawn by
// texture mapping the atlas, compared with the per-pixel render and the ground truth.
struct AtlasArgs {
    std::string scene, outDir, kind = "uniform", magnification = "bilinear";
    int size = 512, image = 0, truth = 4, threads = 0;
    bool quiet = false, mip = false;
    int turntable = 0;   // frames of a turn of the camera about the target (0 = none)
};

// "FILE:LINE" of the k-th [[objects]] table of a scene file ("FILE" if not found).
std::string objectWhere(const std::string& path, int k) {
    std::ifstream in(path);
    std::string line;
    int n = -1;
    for (int no = 1; std::getline(in, line); ++no) {
        const size_t a = line.find_first_not_of(" \t");
        if (a != std::string::npos && line.compare(a, 11, "[[objects]]") == 0 && ++n == k)
            return path + ":" + std::to_string(no);
    }
    return path;
}

// The use of each object's mesh edges (atlas triangles grouped by object; index = object).
std::vector<MeshEdges> objectEdges(const Scene& scene, const std::vector<AtlasTriangle>& tris) {
    std::vector<std::vector<AtlasTriangle>> byObject(scene.objects.size());
    for (const AtlasTriangle& t : tris) byObject[size_t(t.object)].push_back(t);
    std::vector<MeshEdges> out;
    for (const auto& ts : byObject) {
        MeshEdges m = meshEdges(ts);
        // The triangle named by its index in the object's mesh, not in this object's list.
        if (m.firstNonManifold >= 0) m.firstNonManifold = ts[size_t(m.firstNonManifold)].index;
        out.push_back(m);
    }
    return out;
}

// --mip pairs triangles across their edges: refuses an object with an edge on three or more
// triangles ("FILE:LINE: FIELD: ..." of its mesh key, or of its OBJ file). Open edges pass: a
// boundary triangle only has fewer neighbours in the dual graph.
void refuseNonManifold(const Scene& scene, const std::vector<MeshEdges>& edges) {
    for (size_t o = 0; o < edges.size(); ++o) {
        const MeshEdges& m = edges[o];
        if (m.nonManifold == 0) continue;
        throw InputError(scene.objects[o].meshSource + ": " + std::to_string(m.nonManifold) +
                         (m.nonManifold == 1 ? " edge" : " edges") + " on 3 or more triangles (non-manifold; up to " +
                         std::to_string(m.mostTriangles) + " on one edge, the first at triangle " +
                         std::to_string(m.firstNonManifold) +
                         "); --mip pairs triangles across their shared edges, which needs every edge on at most two "
                         "triangles (the strip atlases, without --mip, take this mesh)");
    }
}

// The profile's Fmax (MHz) from scripts/synth/baseline.json, 0 if it has none.
double baselineFmax(const std::string& profile) {
    std::ifstream in(sourceDir() + "/scripts/synth/baseline.json");
    if (!in) return 0;
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.contains("profiles") || !j["profiles"].contains(profile)) return 0;
    const auto& p = j["profiles"][profile];
    return p.contains("fmax_mhz") && p["fmax_mhz"].is_number() ? p["fmax_mhz"].get<double>() : 0;
}

// The profile's Fmax after layout (MHz): the routed profile's post-route figure (the chip timed
// from its routed blocks, assembled_fmax_mhz, as the silicon table gives it; else the slowest
// block's), any other profile's pre-layout Fmax times the routed blocks' worst ratio
// (scripts/synth/layout_derate.json, as docs/HARDWARE.md's silicon table); 0 without it.
double layoutFmax(const std::string& profile, double preLayout) {
    std::ifstream in(sourceDir() + "/scripts/synth/layout_derate.json");
    if (!in) return 0;
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded()) return 0;
    if (j.value("profile", "") == profile) {
        for (const char* key : {"assembled_fmax_mhz", "post_route_fmax_mhz"})
            if (j.contains(key) && j[key].is_number()) return j[key].get<double>();
    }
    return j.contains("ratio") && j["ratio"].is_number() ? preLayout * j["ratio"].get<double>() : 0;
}

int runAtlas(const AtlasArgs& a, const HwArgs& hw) {
    AtlasOptions ao;
    if (!parseAtlasKind(a.kind, &ao.kind)) throw InputError("--atlas: '" + a.kind + "' is not uniform, area or length");
    if (!parseMagnification(a.magnification, &ao.magnification))
        throw InputError("--magnification: '" + a.magnification + "' is not nearest or bilinear");
    ao.size = a.size;
    if (hw.profiles.size() > 1) throw InputError("--profile: atlas takes one profile");
    const Scene scene = opaqueLayer(loadScene(a.scene, a.image, a.image));
    const std::string stem = fs::path(a.scene).stem().string();
    const fs::path dir = a.outDir.empty() ? fs::path("out") / "atlas" / stem : fs::path(a.outDir);

    // Step 1: the triangles (a zero-area one has no chart) and the atlas (section 4).
    const std::vector<AtlasTriangle> tris = sceneTriangles(scene);
    for (const AtlasTriangle& t : tris) {
        const double e = t.longestEdge();
        if (!(t.area() > 1e-12 * e * e))
            throw InputError(objectWhere(a.scene, t.object) + ": objects[" + std::to_string(t.object) +
                             "].mesh: triangle " + std::to_string(t.index) + " of '" + scene.objects[size_t(t.object)].name +
                             "' has zero area (degenerate; check the object's scale)");
    }
    const std::vector<MeshEdges> edges = objectEdges(scene, tris);
    if (a.mip) refuseNonManifold(scene, edges);
    long long openEdges = 0, nonManifoldEdges = 0;
    for (const MeshEdges& m : edges) openEdges += m.open, nonManifoldEdges += m.nonManifold;
    const Atlas atlas = a.mip ? buildMultiresAtlas(tris, ao) : buildAtlas(tris, ao);
    AtlasOptions std0 = ao;
    std0.seamFree = false;
    const Atlas standard = a.mip ? buildMultiresAtlas(tris, std0) : buildAtlas(tris, std0);
    std::optional<Profile> prof;
    if (!hw.profiles.empty()) {
        prof = profileByName(hw.profiles[0], hw.model == "rtl");
        if (std::string why = unsupportedTexture(scene, *prof); !why.empty()) throw InputError(why);
    }

    // Step 2: the fill (one fragment per texel).
    auto say = [&](const std::string& s) {
        if (!a.quiet) std::fprintf(stderr, "%s: %s\n", stem.c_str(), s.c_str());
    };
    say("filling " + std::to_string(atlas.size()) + "^2 atlas");
    AtlasFill fill;
    if (prof) {
        std::unique_ptr<RtlModel> rtl;
        if (hw.model == "rtl") rtl = makeRtlModel(prof->name, hw.sim);
        fill = fillAtlas(scene, atlas, *prof, rtl.get());
    } else {
        fill = fillAtlasReference(scene, atlas, a.threads);
    }

    // Step 3: the view texture-mapped with the atlas; seams; the per-pixel render and the truth.
    say("rendering");
    const std::vector<int> owners = atlas.owners(), stdOwners = standard.owners();
    const AtlasRender near = renderWithAtlas(scene, atlas, fill.reference, owners, Magnification::Nearest);
    const AtlasRender bil = renderWithAtlas(scene, atlas, fill.reference, owners, Magnification::Bilinear);
    const Image blank(standard.size(), standard.size(), 4);
    const AtlasRender stdNear = renderWithAtlas(scene, standard, blank, stdOwners, Magnification::Nearest);
    const AtlasRender stdBil = renderWithAtlas(scene, standard, blank, stdOwners, Magnification::Bilinear);
    RenderOptions ro;
    ro.truthSamples = a.truth;
    ro.threads = a.threads;
    const RenderResult pp = render(scene, ro);
    const ImageDiff dN = compareRgb(near.image, pp.truth), dB = compareRgb(bil.image, pp.truth),
                    dP = compareRgb(pp.filtered, pp.truth), dBP = compareRgb(bil.image, pp.filtered);
    AtlasRender hwBil, tri;
    if (prof) hwBil = renderWithAtlas(scene, atlas, fill.hardware, owners, Magnification::Bilinear);
    std::vector<long long> mixing;
    if (a.mip) {
        tri = renderWithAtlasTrilinear(scene, atlas, mipLevels(fill.reference, owners));
        mixing = mipMixing(atlas, dualGraph(atlas.triangles));
    }

    int minLegs = 1 << 30, maxLegs = 0;
    for (const Chart& c : atlas.charts) minLegs = std::min(minLegs, c.legs), maxLegs = std::max(maxLegs, c.legs);
    nlohmann::json j;
    j["scene"] = a.scene;
    j["atlas"] = a.kind;
    j["size"] = atlas.size();
    j["magnification"] = a.magnification;
    j["triangles"] = atlas.triangles.size();
    j["eq3_edge"] = atlas.eq3Edge;
    j["legs"] = {{"min", minLegs}, {"max", maxLegs}};
    j["mesh_edges"] = {{"open", openEdges}, {"non_manifold", nonManifoldEdges}};
    j["strips"] = atlas.stripCount;
    j["coverage"] = coverage(atlas);
    j["relative_scale"] = relativeScale(atlas);
    j["texel_use"] = texelUse(atlas);
    j["standard_layout"] = {{"coverage", coverage(standard)}, {"relative_scale", relativeScale(standard)}};
    j["paper_table1_rhino"] = {{"uniform", {0.91, 1.75}}, {"area", {0.93, 0.66}}, {"length", {0.93, 0.86}}};
    j["image"] = {{"width", scene.camera.width}, {"height", scene.camera.height}, {"truth_samples", a.truth * a.truth}};
    j["seams"] = {{"pixels", bil.pixels},
                  {"nearest", near.seamPixels}, {"bilinear", bil.seamPixels},
                  {"standard_nearest", stdNear.seamPixels}, {"standard_bilinear", stdBil.seamPixels}};
    j["rms_vs_truth"] = {{"atlas_nearest", dN.rmsError}, {"atlas_bilinear", dB.rmsError}, {"per_pixel", dP.rmsError}};
    j["rms_atlas_bilinear_vs_per_pixel"] = dBP.rmsError;
    if (a.mip) {
        const double dT = compareRgb(tri.image, pp.truth).rmsError;
        j["rms_vs_truth"]["atlas_trilinear"] = dT;
        int minCell = atlas.mipCell;
        for (const Chart& c : atlas.charts) minCell = std::min(minCell, atlas.cellSize(c.legs).x);
        j["mip"] = {{"cell", atlas.mipCell}, {"cell_min", minCell}, {"levels", mixing.size()}, {"mixing_texels", mixing}};
    }
    j["fill"] = {{"texels", fill.texels}, {"reference_seconds", fill.referenceSeconds}};
    std::ostringstream line;
    line << stem << " " << a.kind << " " << atlas.size() << ": C " << coverage(atlas) << ", S " << relativeScale(atlas)
         << ", seams nearest " << near.seamPixels << " bilinear " << bil.seamPixels << " (standard layout "
         << stdNear.seamPixels << " / " << stdBil.seamPixels << "), RMS vs truth: atlas " << dN.rmsError << " / "
         << dB.rmsError;
    if (a.mip) line << " / trilinear " << j["rms_vs_truth"]["atlas_trilinear"].get<double>();
    line << ", per pixel " << dP.rmsError;
    int rc = 0;
    if (prof) {
        const double fmax = baselineFmax(prof->name);
        nlohmann::json f = {{"profile", prof->name}, {"model", hw.model}, {"texels", fill.texels},
                            {"golden_seconds", fill.goldenSeconds}, {"notes", fill.notes},
                            {"vs_reference", {{"rms", compareRgb(fill.hardware, fill.reference).rmsError}}},
                            {"render_bilinear_rms_vs_truth", compareRgb(hwBil.image, pp.truth).rmsError}};
        if (hw.model == "rtl") {
            f["passed"] = fill.passed;
            f["mismatches"] = fill.mismatches;
            f["cycles"] = fill.cycles;
            f["cycles_per_texel"] = fill.texels ? double(fill.cycles) / double(fill.texels) : 0.0;
            f["rtl_seconds"] = fill.rtlSeconds;
            f["gap_rate"] = hw.sim.inputGapRate;
            f["stall_rate"] = hw.sim.outputStallRate;
            f["fmax_mhz"] = fmax > 0 ? nlohmann::json(fmax) : nlohmann::json(nullptr);
            f["fill_ms_at_fmax"] = fmax > 0 ? nlohmann::json(double(fill.cycles) / (fmax * 1e3)) : nlohmann::json(nullptr);
            const double fmaxLayout = fmax > 0 ? layoutFmax(prof->name, fmax) : 0;
            if (fmaxLayout > 0) {
                f["fmax_layout_mhz"] = fmaxLayout;
                f["fill_ms_at_layout_fmax"] = double(fill.cycles) / (fmaxLayout * 1e3);
            }
            // Carr and Hart's Table 3: host synthesis rates (Hz) of 1 and 4 octaves at this size.
            const std::map<int, std::pair<double, double>> table3 = {{256, {9.09, 6.25}}, {512, {2.56, 1.82}},
                                                                     {1024, {0.72, 0.40}}};
            if (auto it = table3.find(atlas.size()); it != table3.end())
                f["paper_table3_host_hz"] = {{"octaves_1", it->second.first}, {"octaves_4", it->second.second}};
            if (fmax > 0 && fill.cycles > 0) f["fill_hz_at_fmax"] = fmax * 1e6 / double(fill.cycles);
            line << "; " << prof->name << " RTL " << fill.mismatches << " mismatches, " << fill.cycles << " cycles";
            if (fmax > 0) line << " = " << double(fill.cycles) / (fmax * 1e3) << " ms at " << fmax << " MHz";
            if (!fill.passed) rc = 1;
        }
        j["hardware"] = f;
    }
    // The turntable: the camera turned about its up axis through the target, the atlas (filled
    // once: it is view-independent) against the per-pixel render, both against the truth;
    // flicker = mean temporal RMS against the truth's own change (animate.h temporalRms).
    std::vector<std::pair<std::string, Image>> turnFrames;
    if (a.turntable > 1) {
        std::vector<Image> prevA, prevP, prevT, prevM;
        double flA = 0, flP = 0, rmsA = 0, rmsP = 0, flM = 0, rmsM = 0;
        const std::vector<Image> levels = a.mip ? mipLevels(fill.reference, owners) : std::vector<Image>();
        for (int k = 0; k < a.turntable; ++k) {
            say("turntable frame " + std::to_string(k + 1) + "/" + std::to_string(a.turntable));
            Scene v = scene;
            const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), 2.0 * M_PI * k / a.turntable, scene.camera.up);
            v.camera.eye = scene.camera.target + glm::dvec3(turn * glm::dvec4(scene.camera.eye - scene.camera.target, 0.0));
            const AtlasRender ar = renderWithAtlas(v, atlas, fill.reference, owners, Magnification::Bilinear);
            const RenderResult pr = render(v, ro);
            rmsA += compareRgb(ar.image, pr.truth).rmsError / a.turntable;
            rmsP += compareRgb(pr.filtered, pr.truth).rmsError / a.turntable;
            Image mr;
            if (a.mip) {
                mr = renderWithAtlasTrilinear(v, atlas, levels).image;
                rmsM += compareRgb(mr, pr.truth).rmsError / a.turntable;
                if (k > 0) flM += temporalRms(prevM[0], mr, prevT[0], pr.truth) / (a.turntable - 1);
                prevM = {mr};
            }
            if (k > 0) {
                flA += temporalRms(prevA[0], ar.image, prevT[0], pr.truth) / (a.turntable - 1);
                flP += temporalRms(prevP[0], pr.filtered, prevT[0], pr.truth) / (a.turntable - 1);
            }
            char name[64];
            std::snprintf(name, sizeof name, "frame_%04d.png", k);
            turnFrames.push_back({std::string("turntable/atlas_") + name, ar.image});
            turnFrames.push_back({std::string("turntable/per_pixel_") + name, pr.filtered});
            prevA = {ar.image};
            prevP = {pr.filtered};
            prevT = {pr.truth};
        }
        j["turntable"] = {{"frames", a.turntable},
                          {"flicker", {{"atlas_bilinear", flA}, {"per_pixel", flP}}},
                          {"rms_vs_truth_mean", {{"atlas_bilinear", rmsA}, {"per_pixel", rmsP}}}};
        if (a.mip) {
            j["turntable"]["flicker"]["atlas_trilinear"] = flM;
            j["turntable"]["rms_vs_truth_mean"]["atlas_trilinear"] = rmsM;
        }
        line << "; turntable " << a.turntable << " frames: flicker atlas " << flA;
        if (a.mip) line << " / trilinear " << flM;
        line << ", per pixel " << flP;
    }

    std::ostringstream md;
    md << "# Atlas: " << stem << " (" << a.kind << ", " << atlas.size() << " x " << atlas.size() << ", seam-free for "
       << a.magnification << ")\n\n"
       << "| measure | ours | paper Table 1 (rhino, " << a.kind << ") |\n|---|---|---|\n"
       << "| coverage C (eq. 1) | " << coverage(atlas) << " | "
       << (ao.kind == AtlasKind::Uniform ? "0.91" : "0.93") << " |\n"
       << "| relative scale S (eq. 2) | " << relativeScale(atlas) << " | "
       << (ao.kind == AtlasKind::Uniform ? "1.75" : ao.kind == AtlasKind::Area ? "0.66" : "0.86") << " |\n"
       << "| triangles | " << atlas.triangles.size() << " | |\n| legs (texels) | " << minLegs << " .. " << maxLegs
       << " | |\n| eq. 3 pair edge | " << atlas.eq3Edge << " | |\n"
       << "| mesh edges: open / non-manifold | " << openEdges << " / " << nonManifoldEdges << " | |\n\n"
       << "![atlas](atlas.png) ![textured, bilinear](render_bilinear.png) ![per-pixel](per_pixel.png) "
       << "![truth](truth.png) ![relative scale (Fig. 7)](scale.png)\n\n"
       << "| seams (screen pixels reading a background or foreign texel) | nearest | bilinear |\n|---|---|---|\n"
       << "| seam-free layout | " << near.seamPixels << " | " << bil.seamPixels << " |\n"
       << "| standard layout (Fig. 2) | " << stdNear.seamPixels << " | " << stdBil.seamPixels << " |\n\n"
       << "| RMS vs " << a.truth << "x" << a.truth << " truth | value |\n|---|---|\n"
       << "| atlas, nearest | " << dN.rmsError << " |\n| atlas, bilinear | " << dB.rmsError << " |\n"
       << "| per-pixel render | " << dP.rmsError << " |\n";
    if (a.mip) {
        md << "| atlas, trilinear (MIP) | " << j["rms_vs_truth"]["atlas_trilinear"].get<double>() << " |\n\n"
           << "MIP texels averaging non-neighbours, level 0 up: " << j["mip"]["mixing_texels"].dump() << "\n";
    }
    if (j.contains("turntable"))
        md << "\nTurntable, " << a.turntable << " frames: flicker (temporal RMS vs the truth) atlas bilinear "
           << j["turntable"]["flicker"]["atlas_bilinear"].get<double>() << ", per-pixel "
           << j["turntable"]["flicker"]["per_pixel"].get<double>() << "; mean RMS vs truth atlas "
           << j["turntable"]["rms_vs_truth_mean"]["atlas_bilinear"].get<double>() << ", per-pixel "
           << j["turntable"]["rms_vs_truth_mean"]["per_pixel"].get<double>() << ".\n";
    if (j.contains("hardware") && j["hardware"].contains("cycles"))
        md << "\nFill through " << prof->name << " RTL: " << fill.texels << " texels, " << fill.cycles << " cycles, "
           << fill.mismatches << " mismatches" << (j["hardware"]["fill_ms_at_fmax"].is_null() ? std::string()
               : ", " + j["hardware"]["fill_ms_at_fmax"].dump() + " ms at " + j["hardware"]["fmax_mhz"].dump() + " MHz")
           << (j["hardware"].contains("fill_ms_at_layout_fmax")
               ? ", " + j["hardware"]["fill_ms_at_layout_fmax"].dump() + " ms at " + j["hardware"]["fmax_layout_mhz"].dump() +
                     " MHz after layout" : std::string())
           << ".\n";
    if (j.contains("hardware") && j["hardware"].contains("paper_table3_host_hz") && j["hardware"].contains("fill_hz_at_fmax"))
        md << "Fill rate " << j["hardware"]["fill_hz_at_fmax"].get<double>() << " Hz; the paper's host (Table 3) at "
           << atlas.size() << "^2: " << j["hardware"]["paper_table3_host_hz"]["octaves_1"].get<double>() << " Hz (1 octave), "
           << j["hardware"]["paper_table3_host_hz"]["octaves_4"].get<double>() << " Hz (4 octaves).\n";

    OutputFiles out(dir);
    writeImage(fill.reference, out("atlas.png"));
    if (prof) writeImage(fill.hardware, out("atlas_" + hw.model + ".png"));
    writeImage(near.image, out("render_nearest.png"));
    writeImage(bil.image, out("render_bilinear.png"));
    if (a.mip) writeImage(tri.image, out("render_trilinear.png"));
    writeImage(pp.filtered, out("per_pixel.png"));
    writeImage(pp.truth, out("truth.png"));
    writeImage(relativeScalePicture(scene, atlas), out("scale.png"));
    if (!turnFrames.empty()) fs::create_directories(dir / "turntable");
    for (const auto& [name, img] : turnFrames) writeImage(img, out(name));
    writeTextFile(out("atlas.json"), j.dump(2) + "\n");
    writeTextFile(out("atlas.md"), md.str());
    out.keep();
    std::cout << line.str() << " -> " << dir.string() << "\n";
    if (rc) std::cout << fill.scoreboard;
    return rc;
}

}  // namespace

// CLI11's Range lets NaN through (every comparison with NaN is false).
const CLI::Validator kFinite(
    [](std::string& s) {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        return std::isfinite(v) ? std::string() : std::string("must be a finite number");
    },
    "FINITE");

// An output file given with -o must not be an existing folder.
void checkOutFile(const std::string& flag, const std::string& path) {
    if (!path.empty() && path != "-" && fs::is_directory(path))
        throw InputError(flag + ": '" + path + "' is a folder; give a file name");
}

int main(int argc, char** argv) {
    CLI::App app{"pst: cycle-level simulator of the Hart et al. 1999 procedural solid-texturing ASIC"};
    app.require_subcommand(1);

    RenderArgs ra;
    auto* render = app.add_subcommand("render", "Render a scene through the reference model");
    render->add_option("scene", ra.scene, "Scene file (TOML, see scenes/README.md)")->required()->check(CLI::ExistingFile);
    render->add_option("-o,--out", ra.outDir, "Output folder (default out/<scene name>)");
    render->add_option("--size", ra.size, "Square image size, overrides the scene's")->check(CLI::Range(1, 16384));
    render->add_option("--width", ra.width, "Image width, overrides the scene's")->check(CLI::Range(1, 16384));
    render->add_option("--height", ra.height, "Image height, overrides the scene's")->check(CLI::Range(1, 16384));
    render->add_option("--truth", ra.truth, "Also render the ground truth with N x N jittered samples per pixel")->check(CLI::Range(1, 64));
    render->add_option("--seed", ra.seed, "Jitter seed of the ground truth");
    render->add_option("-j,--threads", ra.threads, "Threads (default: all cores)")->check(CLI::Range(0, 256));
    render->add_flag("-q,--quiet", ra.quiet, "No progress on stderr");
    const std::vector<std::string> bandlimitNames{"off", "footprint", "isotropic", "anisotropic"};
    render->add_option("--bandlimit", ra.bandlimit, "Every texture's bandlimited octaves: off, footprint, isotropic or "
                       "anisotropic (scenes/README.md)")
        ->check(CLI::IsMember(bandlimitNames));
    const std::vector<std::string> filterNames{"none", "mip", "mip_linear", "sat", "box", "trapezoid"};
    render->add_option("--filter", ra.filter, "Every texture's filter kind: none, mip, mip_linear, sat, box or trapezoid")
        ->check(CLI::IsMember(filterNames));
    render->add_option("--variants", ra.variants, "Also the filtered image with every texture's filter (and bandlimit) "
                       "replaced, per KIND[+BANDLIMIT] (e.g. trapezoid sat+footprint), compared with the truth (reference only)")
        ->delimiter(',');

    HwArgs hw;
    auto addSimOptions = [&hw](CLI::App* sc) {
        sc->add_option("--sim-seed", hw.sim.seed, "Seed of the random input gaps and output stalls");
        sc->add_option("--gap-rate", hw.sim.inputGapRate, "Probability of an idle input cycle")->check(kFinite & CLI::Range(0.0, 0.95));
        sc->add_option("--stall-rate", hw.sim.outputStallRate, "Probability of out_ready low in a cycle")->check(kFinite & CLI::Range(0.0, 0.95));
        sc->add_option("--timeout", hw.sim.timeoutCycles, "Cycle limit of one stream (0 = automatic)");
    };
    render->add_option("--profile", hw.profiles, "Hardware profile(s): full, reduced or a profile file; renders through the RTL")
        ->allow_extra_args(false);
    render->add_option("--model", hw.model, "Hardware model for --profile: rtl or golden")->check(CLI::IsMember({"rtl", "golden"}));
    render->add_option("--trace", hw.trace, "FST waveform of the RTL run (off unless given)");
    render->add_option("--trace-start", hw.sim.traceStart, "First traced cycle");
    render->add_option("--trace-end", hw.sim.traceEnd, "Last traced cycle");
    render->add_option("--html", hw.html, "With --profile: also an HTML page of the runs (table, image viewer)");
    addSimOptions(render);

    std::string texPath, fragPath, evalOut, filterName, evalModel = "reference";
    auto* eval = app.add_subcommand("eval", "Evaluate a texture at the fragments of a fragment file");
    eval->add_option("-t,--texture", texPath, "Texture block (TOML, the keys of [textures.NAME])")->required()->check(CLI::ExistingFile);
    eval->add_option("-f,--fragments", fragPath, "Fragment file: s t r ds/dx dt/dx dr/dx ds/dy dt/dy dr/dy per line")->required()->check(CLI::ExistingFile);
    eval->add_option("-o,--out", evalOut, "Output file (default stdout)");
    eval->add_option("--filter", filterName, "Override the texture's filter: none, mip, mip_linear, sat, box, trapezoid");
    eval->add_option("--model", evalModel, "reference (double), golden (fixed point) or rtl (verilated)")
        ->check(CLI::IsMember({"reference", "golden", "rtl"}));
    eval->add_option("--profile", hw.profiles, "Hardware profile for --model golden|rtl")->allow_extra_args(false);

    std::vector<std::string> regScenes;
    int regSize = 64;
    std::string regOut, regImages;
    auto* regress = app.add_subcommand("regress", "Every scene through every profile's RTL, checked against the golden model");
    regress->add_option("scenes", regScenes, "Scene files (default: scenes/*.toml)")->check(CLI::ExistingFile);
    regress->add_option("--size", regSize, "Square image size")->check(CLI::Range(1, 4096));
    regress->add_option("--profile", hw.profiles, "Profiles (default: every verilated profile; one per --profile)")
        ->allow_extra_args(false);
    regress->add_option("-o,--out", regOut, "JSON summary file");
    std::string regJunit;
    regress->add_option("--junit", regJunit, "JUnit XML of the runs (one test case per scene x profile, or per profile with --random)");
    regress->add_option("--images", regImages, "Also write <dir>/<scene>/<profile>/{rtl,reference,difference}.png");
    std::string regHtml;
    regress->add_option("--html", regHtml, "Also an HTML page: table, image viewer per scene (images to --images, "
                        "default the page's folder; JSON to -o, default beside the page)");
    addSimOptions(regress);
    RandomRegressOptions rnd;
    uint64_t rndCount = 0;
    bool rndQuiet = false;
    auto* rndOpt = regress->add_option("--random", rndCount, "Constrained-random mode: N random fragments per profile (random textures, gaps, stalls) instead of scenes")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32));
    regress->add_option("--seed", rnd.seed, "Seed of --random")->needs(rndOpt);
    regress->add_option("--from", rnd.from, "Replay --random from the fragment with this index (starts at its segment)")->needs(rndOpt);
    regress->add_option("--batch", rnd.maxBatch, "Most fragments per random texture")->check(CLI::Range(1, 1 << 20))->needs(rndOpt);
    regress->add_flag("--probes", rnd.probes, "Sample the octave-stage probes in --random (names the first bad unit)")->needs(rndOpt);
    regress->add_flag("-q,--quiet", rndQuiet, "No progress on stderr");
    uint64_t injectAssert = UINT64_MAX;
    regress->add_option("--inject-assert", injectAssert, "Self-test: once fragment I (of --random, or of each scene run) is in "
                        "the RTL, write a register while the pipeline is busy; the RTL's RegWriteOnlyWhenIdle assertion "
                        "must fire and fail the run")
        ->check(CLI::Range(uint64_t(0), (uint64_t(1) << 32) - 1));
    bool regList = false;
    regress->add_flag("--list", regList, "Print the runs and exit (what scripts/regress.py splits into shards): "
                      "scene file TAB profile per line; with --random 'profile NAME' lines, then 'segment I' per "
                      "segment the run simulates (I: its first fragment)");

    std::string fragScene, fragOut;
    int fragSize = 0, fragLayer = 0;
    auto* frag = app.add_subcommand("fragments", "Write a scene's fragment stream as a fragment file");
    frag->add_option("scene", fragScene, "Scene file")->required()->check(CLI::ExistingFile);
    frag->add_option("--size", fragSize, "Square image size, overrides the scene's")->check(CLI::Range(1, 16384));
    frag->add_option("--layer", fragLayer, "Layer (0 = opaque pass)");
    frag->add_option("-o,--out", fragOut, "Output file (default stdout)");

    std::string cmpA, cmpB;
    auto* cmp = app.add_subcommand("compare", "RMS and PSNR between two images (RGB)");
    cmp->add_option("a", cmpA)->required()->check(CLI::ExistingFile);
    cmp->add_option("b", cmpB)->required()->check(CLI::ExistingFile);

    AnimateArgs an;
    auto* animate = app.add_subcommand("animate", "Render a scene's time track: PNG frames, videos, flicker.json");
    animate->add_option("scene", an.scene, "Scene file with an [animation] track")->required()->check(CLI::ExistingFile);
    animate->add_option("--frames", an.frames, "Frames (default: the scene's animation.frames)")->check(CLI::Range(1, 10000));
    animate->add_option("--size", an.size, "Square image size, overrides the scene's")->check(CLI::Range(1, 4096));
    animate->add_option("--truth", an.truth, "N x N ground truth per frame (the flicker metric needs it)")->check(CLI::Range(1, 64));
    animate->add_option("--fps", an.fps, "Video frame rate (default: the scene's animation.fps)")->check(kFinite & CLI::Range(0.1, 240.0));
    animate->add_option("--profile", an.profiles, "Also through the hardware model(s) of these profiles, scoreboarded")
        ->allow_extra_args(false);
    animate->add_option("--model", an.model, "Hardware model for --profile: rtl or golden")->check(CLI::IsMember({"rtl", "golden"}));
    animate->add_option("-o,--out", an.outDir, "Output folder (default out/anim/<scene name>)");
    animate->add_option("-j,--threads", an.threads, "Threads (default: all cores)")->check(CLI::Range(0, 256));
    bool noVideo = false, animQuiet = false;
    animate->add_flag("--no-video", noVideo, "PNG frames and flicker.json only");
    animate->add_option("--bandlimit", an.bandlimit, "Every texture's bandlimited octaves: off, footprint, isotropic or "
                        "anisotropic (scenes/README.md)")
        ->check(CLI::IsMember(bandlimitNames));
    animate->add_option("--filter", an.filter, "Every texture's filter kind: none, mip, mip_linear, sat, box or trapezoid")
        ->check(CLI::IsMember(filterNames));
    std::vector<std::string> animVariants;
    animate->add_option("--variants", animVariants, "Also a reference stream per KIND[+BANDLIMIT] (every texture's filter "
                        "and bandlimit replaced), with its flicker")
        ->delimiter(',');
    animate->add_flag("-q,--quiet", animQuiet, "No progress on stderr");

    AtlasArgs at;
    auto* atlasCmd = app.add_subcommand("atlas", "Texture-atlas mode: fill a meshed atlas of the scene through the models, render with it");
    atlasCmd->add_option("scene", at.scene, "Scene file (its layer-0 objects)")->required()->check(CLI::ExistingFile);
    atlasCmd->add_option("--atlas", at.kind, "Atlas kind: uniform, area or length (Carr and Hart section 4)");
    atlasCmd->add_option("--size", at.size, "Atlas resolution H (H x H texels)")->check(CLI::Range(2, 4096));
    atlasCmd->add_flag("--mip", at.mip, "Multiresolution atlas of the --atlas kind (section 4.3, METIS quadtree; power-of-two "
                       "cells, per pair for area and length; --size a power of two) and a trilinear render");
    atlasCmd->add_option("--turntable", at.turntable, "Also N views turning about the target: the atlas render's "
                         "flicker against the per-pixel render's (temporal RMS vs the truth)")->check(CLI::Range(2, 720));
    atlasCmd->add_option("--magnification", at.magnification, "Seam-free for: nearest or bilinear (default bilinear)");
    atlasCmd->add_option("--image", at.image, "Square view size, overrides the scene's")->check(CLI::Range(1, 4096));
    atlasCmd->add_option("--truth", at.truth, "N x N jittered samples per pixel of the ground truth")->check(CLI::Range(1, 64));
    atlasCmd->add_option("--profile", hw.profiles, "Also fill through this profile's golden model and RTL (scoreboarded)")
        ->allow_extra_args(false);
    atlasCmd->add_option("--model", hw.model, "Hardware model for --profile: rtl or golden")->check(CLI::IsMember({"rtl", "golden"}));
    atlasCmd->add_option("-o,--out", at.outDir, "Output folder (default out/atlas/<scene name>)");
    atlasCmd->add_option("-j,--threads", at.threads, "Threads (default: all cores)")->check(CLI::Range(0, 256));
    atlasCmd->add_flag("-q,--quiet", at.quiet, "No progress on stderr");
    addSimOptions(atlasCmd);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    try {
        if (*render) {
            if (!hw.html.empty() && hw.profiles.empty()) throw InputError("--html: needs --profile");
            const bool traceOpts = !hw.trace.empty() || render->count("--trace-start") || render->count("--trace-end");
            if (traceOpts && hw.profiles.empty()) throw InputError("--trace: needs --profile (the waves are the RTL's)");
            if (traceOpts && hw.model != "rtl") throw InputError("--trace: needs --model rtl (the golden model has no waves)");
            if (traceOpts && hw.trace.empty()) throw InputError("--trace-start, --trace-end: need --trace FILE");
            if (hw.sim.traceStart > hw.sim.traceEnd)
                throw InputError("--trace-start: " + std::to_string(hw.sim.traceStart) + " is after --trace-end " +
                                 std::to_string(hw.sim.traceEnd));
            if (!ra.outDir.empty() && fs::exists(ra.outDir) && !fs::is_directory(ra.outDir))
                throw InputError("-o: '" + ra.outDir + "' is a file; give a folder");
            return hw.profiles.empty() ? runRender(ra) : runHardwareRender(ra, hw);
        }
        if (*eval) {
            if (evalModel != "reference" && hw.profiles.empty()) hw.profiles = {"full"};
            checkOutFile("-o", evalOut);
            return runEval(texPath, fragPath, evalOut, filterName, evalModel, hw);
        }
        if (*regress) {
            if (hw.profiles.empty()) hw.profiles = rtlProfiles();
            checkOutFile("-o", regOut);
            checkOutFile("--junit", regJunit);
            if (rndCount > 0) {
                if (!regScenes.empty()) throw InputError("--random: takes no scene files");
                if (!regImages.empty()) throw InputError("--images: not with --random (it writes no images)");
                if (!regHtml.empty()) throw InputError("--html: not with --random (it writes no images)");
                if (regress->get_option("--size")->count()) throw InputError("--size: not with --random");
                if (rnd.from + rndCount > (uint64_t(1) << 32))
                    throw InputError("--from: fragment indices are 32-bit tags (from + N <= 2^32)");
                rnd.fragments = rndCount;
                rnd.injectAssert = injectAssert;
                if (regList) {
                    for (const auto& n : hw.profiles) std::cout << "profile " << profileByName(n, true).name << "\n";
                    for (uint64_t s : segmentStarts(rnd)) std::cout << "segment " << s << "\n";
                    return 0;
                }
                return runRandom(hw, rnd, rndQuiet, regOut, regJunit);
            }
            if (regScenes.empty()) {
                for (const auto& e : fs::directory_iterator(fs::path(sourceDir()) / "scenes"))
                    if (e.path().extension() == ".toml") regScenes.push_back(e.path().string());
                std::sort(regScenes.begin(), regScenes.end());
            }
            if (injectAssert != UINT64_MAX) hw.sim.busyWriteAfter = injectAssert + 1;
            if (regList) {
                std::vector<std::string> names;
                for (const auto& n : hw.profiles) names.push_back(profileByName(n, true).name);
                for (const auto& sc : regScenes)
                    for (const auto& n : names) std::cout << sc << "\t" << n << "\n";
                return 0;
            }
            if (regHtml.empty()) return runRegress(regScenes, regSize, hw, regOut, regImages, regJunit);
            const fs::path page(regHtml), dir = page.parent_path().empty() ? fs::path(".") : page.parent_path();
            const std::string json = regOut.empty() ? (dir / (page.stem().string() + ".json")).string() : regOut;
            const std::string images = regImages.empty() ? dir.string() : regImages;
            const int rc = runRegress(regScenes, regSize, hw, json, images, regJunit);
            return std::max(rc, writeHtmlPage(regHtml, {"--regress", json, "--images", images}));
        }
        if (*animate) {
            an.video = !noVideo;
            an.variants = parseVariants(animVariants);
            an.loadProfile = [&an](const std::string& n) { return profileByName(n, an.model == "rtl"); };
            // One line per frame and model (rewritten in place on a terminal).
            if (!animQuiet)
                an.progress = [name = fs::path(an.scene).stem().string(), tty = isatty(STDERR_FILENO)](
                                  const std::string& phase, double frac) {
                    std::fprintf(stderr, tty ? "\r%s: %-28s %5.1f%%" : "%s: %s %.1f%%\n", name.c_str(), phase.c_str(),
                                 100.0 * frac);
                    if (tty && frac >= 1.0) std::fprintf(stderr, "\n");
                };
            return runAnimate(an);
        }
        if (*frag) {
            checkOutFile("-o", fragOut);
            return runFragments(fragScene, fragSize, fragLayer, fragOut);
        }
        if (*cmp) return runCompare(cmpA, cmpB);
        if (*atlasCmd) {
            if (!at.outDir.empty() && fs::exists(at.outDir) && !fs::is_directory(at.outDir))
                throw InputError("-o: '" + at.outDir + "' is a file; give a folder");
            return runAtlas(at, hw);
        }
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 2;
}
