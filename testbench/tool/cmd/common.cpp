#include "common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "driver.h"
#include "source_dir.h"

extern "C" char** environ;

namespace pst::cli {

const std::vector<std::string> kBandlimitNames{"off", "footprint", "isotropic", "anisotropic"};
const std::vector<std::string> kFilterNames{"none", "mip", "mip_linear", "sat", "box", "trapezoid"};

const CLI::Validator kFinite(
    [](std::string& s) {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        return std::isfinite(v) ? std::string() : std::string("must be a finite number");
    },
    "FINITE");

void addSimOptions(CLI::App* sc, HwArgs& hw) {
    sc->add_option("--sim-seed", hw.sim.seed, "Seed of the random input gaps and output stalls");
    sc->add_option("--gap-rate", hw.sim.inputGapRate, "Probability of an idle input cycle")->check(kFinite & CLI::Range(0.0, 0.95));
    sc->add_option("--stall-rate", hw.sim.outputStallRate, "Probability of out_ready low in a cycle")->check(kFinite & CLI::Range(0.0, 0.95));
    sc->add_option("--timeout", hw.sim.timeoutCycles, "Cycle limit of one stream (0 = automatic)");
}

const std::vector<std::string> kSimOptions{"--sim-seed", "--gap-rate", "--stall-rate", "--timeout"};

void refuseGiven(const CLI::App* app, const std::vector<std::string>& names, const std::string& why) {
    for (const auto& n : names)
        if (app->count(n) > 0) throw InputError(n + ": " + why);
}

void refuseHardwareOptionsWithoutModel(const CLI::App* app, const HwArgs& hw) {
    if (hw.profiles.empty()) {
        std::vector<std::string> names = kSimOptions;
        names.insert(names.begin(), "--model");
        refuseGiven(app, names, "needs --profile (it sets the hardware model's run; without --profile none runs)");
    }
    if (hw.model != "rtl") refuseGiven(app, kSimOptions, "needs --model rtl (the golden model has no cycles)");
}

std::string profileHelp(const std::string& what) {
    std::string list;
    for (const auto& n : rtlProfiles()) list += (list.empty() ? "" : ", ") + n;
    return what + " (verilated in this build: " + (list.empty() ? "none" : list) +
           "; golden: any name in rtl/configs or a profile file)";
}

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

void checkVariants(const Scene& scene, const std::vector<FilterVariant>& variants) {
    for (const auto& v : variants)
        for (const auto& t : scene.textures)
            if (std::string why = bandlimitUnsupported(t, v.bandlimit); !why.empty())
                throw InputError("--variants: " + v.name + ": texture '" + t.name + "': " + why);
}

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

EtaProgress::EtaProgress(std::string name, size_t total, bool quiet)
    : name_(std::move(name)), total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO)),
      t0_(std::chrono::steady_clock::now()) {}

void EtaProgress::step(const std::string& what) {
    ++done_;
    if (quiet_ || total_ == 0) return;
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    // Not a terminal (a log): the first step, then at most one line per 10 s, and the last.
    if (!tty_ && done_ > 1 && done_ < total_ && el - lastLine_ < 10.0) return;
    lastLine_ = el;
    const double eta = done_ ? el / double(done_) * double(total_ - std::min(done_, total_)) : 0.0;
    std::fprintf(stderr, tty_ ? "\r%s: %zu/%zu runs (%5.1f%%), %s, elapsed %.0f s, ETA %.0f s\033[K"
                              : "%s: %zu/%zu runs (%.1f%%), %s, elapsed %.0f s, ETA %.0f s\n",
                 name_.c_str(), done_, total_, 100.0 * double(done_) / double(total_), what.c_str(), el, eta);
    std::fflush(stderr);
}

void EtaProgress::finish() {
    if (!quiet_ && tty_ && done_) std::fprintf(stderr, "\n");
}

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

Profile profileByName(const std::string& name, bool rtl) {
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

OutputFiles::OutputFiles(const fs::path& dir) : dir_(dir), created_(!fs::exists(dir)) { fs::create_directories(dir); }

std::string OutputFiles::operator()(const std::string& name) {
    const fs::path f = dir_ / name;
    if (!fs::exists(f)) files_.push_back(f);   // never remove what was there before
    return f.string();
}

OutputFiles::~OutputFiles() {
    if (keep_) return;
    std::error_code ec;
    for (const auto& f : files_) fs::remove(f, ec);
    if (created_) fs::remove(dir_, ec);   // only if empty
}

void checkTracePath(const std::string& trace) {
    const fs::path dir = fs::path(trace).parent_path();
    if (!dir.empty() && !fs::is_directory(dir))
        throw InputError("--trace: folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(trace)) throw InputError("--trace: '" + trace + "' is a folder, not a file");
}

void checkOutFile(const std::string& flag, const std::string& path) {
    if (path.empty() || path == "-") return;
    if (fs::is_directory(path)) throw InputError(flag + ": '" + path + "' is a folder; give a file name");
    // The file's folder must be there (the writers do not make it), checked before any work.
    const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError(flag + ": '" + path + "': folder '" + dir.string() + "' does not exist");
    if (access(dir.c_str(), W_OK | X_OK) != 0)
        throw InputError(flag + ": '" + path + "': folder '" + dir.string() + "' is not writable: " + std::strerror(errno));
}

void checkOutDir(const std::string& flag, const std::string& path) {
    if (!path.empty() && fs::exists(path) && !fs::is_directory(path))
        throw InputError(flag + ": '" + path + "' is a file; give a folder");
}

void checkNotInput(const std::string& flag, const std::string& out, const std::vector<std::string>& inputs) {
    if (out.empty() || out == "-") return;
    std::error_code ec;
    for (const auto& in : inputs)
        if (!in.empty() && fs::equivalent(out, in, ec))
            throw InputError(flag + ": '" + out + "' is the input '" + in + "' of this run; it would be overwritten");
}

void checkCreatableDir(const std::string& flag, const std::string& dir) {
    if (dir.empty()) return;
    std::error_code ec;
    fs::path p = fs::absolute(dir, ec);
    if (ec) throw InputError(flag + ": '" + dir + "' cannot be created (" + ec.message() + ")");
    // The nearest folder that exists: it must be a folder, and writable if something is to be made in it.
    const bool exists = fs::exists(p, ec);
    while (!fs::exists(p, ec) && p.has_parent_path() && p.parent_path() != p) p = p.parent_path();
    if (!fs::is_directory(p, ec))
        throw InputError(flag + ": '" + dir + "' cannot be created: '" + p.string() + "' is not a folder");
    if (access(p.c_str(), W_OK | X_OK) != 0)
        throw InputError(flag + ": '" + dir + "' " + (exists ? "is not writable" : "cannot be created") + ": '" +
                         p.string() + "': " + std::strerror(errno));
}

void checkCreatableFileDir(const std::string& flag, const std::string& file) {
    if (file.empty() || file == "-") return;
    const fs::path dir = fs::path(file).parent_path();
    checkCreatableDir(flag, dir.empty() ? "." : dir.string());
}

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

std::string unsupportedTexture(const Scene& scene, const Profile& p) {
    for (const auto& o : scene.objects)
        if (std::string why = hardwareUnsupported(p, scene.textures[o.texture]); !why.empty()) return why;
    return "";
}

}  // namespace pst::cli
