#include "common.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <csignal>
#include <cstring>
#include <iostream>

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include "driver.h"
#include "source_dir.h"


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

void addProfileOptions(CLI::App* sc, std::vector<std::string>& profiles, std::string& model, const std::string& what) {
    sc->add_option("--profile", profiles, profileHelp(what))->allow_extra_args(false);
    sc->add_option("--model", model, "Hardware model for --profile: rtl or golden")->check(CLI::IsMember({"rtl", "golden"}));
}

void addTextureOverrideOptions(CLI::App* sc, std::string& bandlimit, std::string& filter, std::string& widthCap) {
    sc->add_option("--bandlimit", bandlimit, "Every texture's bandlimited octaves: off, footprint, isotropic or "
                   "anisotropic (scenes/README.md; default: as the scene says)")
        ->check(CLI::IsMember(kBandlimitNames));
    sc->add_option("--filter", filter, "Every texture's filter kind: none, mip, mip_linear, sat, box or trapezoid "
                   "(default: as the scene says)")
        ->check(CLI::IsMember(kFilterNames));
    sc->add_option("--width-cap", widthCap, "Every texture's filter-width cap: on or off (w <= sqrt(12 sum a_i^2) sd(n), "
                   "none with a non-constant quadric; docs/HARDWARE.md unit 5; a --profile needs filter.width_cap = "
                   "\"on\"; default: as the scene says)")
        ->check(CLI::IsMember(std::vector<std::string>{"on", "off"}));
}

bool checkTraceOptions(const CLI::App* sc, const std::string& trace, const std::vector<std::string>& profiles,
                       const std::string& model, const std::vector<std::string>& window) {
    bool given = !trace.empty();
    std::string names;
    for (const auto& n : window) {
        given = given || sc->count(n) > 0;
        names += (names.empty() ? "" : ", ") + n;
    }
    if (given && profiles.empty()) throw InputError("--trace: needs --profile (the waves are the RTL's)");
    if (given && model != "rtl") throw InputError("--trace: needs --model rtl (the golden model has no waves)");
    if (given && trace.empty()) throw InputError(names + ": need --trace FILE");
    return given;
}

void checkTraceWindow(const SimOptions& sim) {
    if (sim.traceStart > sim.traceEnd)
        throw InputError("--trace-start: " + std::to_string(sim.traceStart) + " is after --trace-end " +
                         std::to_string(sim.traceEnd));
}

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

void overrideTextures(Scene& scene, const std::string& bandlimit, const std::string& filter,
                      const std::string& widthCap) {
    for (auto& t : scene.textures) {
        if (!widthCap.empty()) {
            t.widthCap = widthCap == "on";
            t.widthCapSource.clear();   // the option's, not the scene line's
        }
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

void writeHtmlPage(const std::string& page, const std::string& shown, std::vector<std::string> args) {
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string script = sourceDir() + "/scripts/report.py";
    args.insert(args.begin(), {python, script, "--html", page});
    const bool ok = spawnAndWait(args);
    throwIfInterrupted();
    if (!ok) throw std::runtime_error("--html: " + script + " did not write '" + shown + "' (nothing of this run is written)");
}

void commitWithPage(Outputs& outputs, const std::string& page, const std::string& shown, std::vector<std::string> args) {
    if (!shown.empty()) {
        const std::vector<std::string> st = outputs.stagedArgs();
        args.insert(args.end(), st.begin(), st.end());
        writeHtmlPage(page, shown, args);
    }
    outputs.commit();
    if (!shown.empty()) std::cout << "page: " << shown << "\n";
}

Profile profileByName(const std::string& name, bool rtl, bool hasModelOption) {
    // A verilated profile's name: the registry's profile (parsed once, sim/rtl_registry.cpp.in).
    const bool registered = !isProfileFile(name) && !rtlProfilePath(name).empty();
    Profile p = registered ? rtlProfile(name) : loadNamedProfile(name, sourceDir());
    if (!rtl) return p;
    const std::string verilated = rtlProfilePath(p.name);
    if (verilated.empty()) {
        std::string list;
        for (const auto& n : rtlProfiles()) list += (list.empty() ? "" : ", ") + n;
        throw InputError(p.path + ": profile '" + p.name + "' has no verilated model in this build (verilated: " + list +
                         "; add it with -DPST_PROFILES or -DPST_EXTRA_PROFILE_DIR" +
                         (hasModelOption ? ", or use --model golden)" : ")"));
    }
    const Profile& v = rtlProfile(p.name);
    if (std::string key = profileDifference(p, v); !key.empty())
        throw InputError(p.path + ": " + key + ": differs from the profile the '" + p.name + "' RTL was verilated from (" +
                         verilated + "); rename the profile or verilate it (-DPST_EXTRA_PROFILE_DIR)");
    return p;
}

namespace {

extern "C" void onStopSignal(int sig) { gInterruptSignal.store(sig); }

// SIGINT and SIGTERM held back (the commit's renames are not cut short).
struct BlockStopSignals {
    sigset_t old;
    BlockStopSignals() {
        sigset_t s;
        sigemptyset(&s);
        sigaddset(&s, SIGINT);
        sigaddset(&s, SIGTERM);
        sigaddset(&s, SIGHUP);
        pthread_sigmask(SIG_BLOCK, &s, &old);
    }
    ~BlockStopSignals() { pthread_sigmask(SIG_SETMASK, &old, nullptr); }
};

// The path made absolute and normal, without a trailing separator.
fs::path normalPath(const std::string& p) {
    fs::path a = fs::absolute(p).lexically_normal();
    if (a.filename().empty() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();
    return a;
}

// A killed run (SIGKILL, a power cut) cannot remove its temporary folder: the next run writing
// into the same folder removes every `.pst-tmp-PID` and `.NAME.pst-tmp-PID` there whose process
// no longer exists (a live process, or one of another user, is left alone).
void removeDeadStages(const fs::path& dir) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const size_t at = name.rfind(".pst-tmp-");
        if (name.empty() || name[0] != '.' || at == std::string::npos) continue;
        const std::string digits = name.substr(at + 9);
        if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
        const pid_t pid = static_cast<pid_t>(std::stol(digits));
        if (pid <= 0 || pid == getpid() || kill(pid, 0) == 0 || errno != ESRCH) continue;
        std::error_code rm;
        fs::remove_all(it->path(), rm);
    }
}

}  // namespace

void installInterruptHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onStopSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;   // no SA_RESTART: a wait for a child returns and passes it on
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    sigaction(SIGHUP, &sa, nullptr);   // the terminal closed
}

void endByInterrupt(int sig) {
    std::cout.flush();
    std::fprintf(stderr, "pst: stopped by %s; this run's outputs were not written\n",
                 sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : sig == SIGHUP ? "SIGHUP" : "a signal");
    std::fflush(stderr);
    std::signal(sig, SIG_DFL);
    sigset_t s;
    sigemptyset(&s);
    sigaddset(&s, sig);
    pthread_sigmask(SIG_UNBLOCK, &s, nullptr);
    std::raise(sig);
    std::_Exit(128 + sig);
}

fs::path Outputs::staged(const std::string& flag, const std::string& target, bool isDir) {
    std::error_code ec;
    const fs::path p = normalPath(target);
    for (const Stage& s : stages_) {
        const fs::path rel = p.lexically_relative(s.root);
        if (!rel.empty() && *rel.begin() != "..") return rel == "." ? s.tmp : s.tmp / rel;
    }
    // The folder the output goes to, and the nearest folder on the way that exists.
    fs::path existing = isDir ? p : p.parent_path(), missing;
    while (!fs::exists(existing, ec) && existing.has_parent_path() && existing.parent_path() != existing)
        missing = existing, existing = existing.parent_path();
    if (!fs::is_directory(existing, ec))
        throw InputError(flag + ": '" + target + "' cannot be written: '" + existing.string() + "' is not a folder");
    const std::string pid = std::to_string(getpid());
    Stage s;
    s.missing = !missing.empty();
    s.root = s.missing ? missing : existing;
    s.tmp = existing / (s.missing ? "." + missing.filename().string() + ".pst-tmp-" + pid : ".pst-tmp-" + pid);
    fs::remove_all(s.tmp, ec);   // a dead run's of the same process id
    removeDeadStages(existing);
    if (!fs::create_directory(s.tmp, ec))
        throw InputError(flag + ": '" + target + "' cannot be written: cannot make a folder in '" + existing.string() +
                         "' (" + ec.message() + ")");
    stages_.push_back(s);
    return staged(flag, target, isDir);
}

std::vector<std::string> Outputs::stagedArgs() const {
    std::vector<std::string> args;
    for (const Stage& s : stages_) args.insert(args.end(), {"--staged", s.tmp.string() + "=" + s.root.string()});
    return args;
}

std::string Outputs::dir(const std::string& flag, const std::string& target) {
    const fs::path d = staged(flag, target, true);
    fs::create_directories(d);
    return d.string();
}

std::string Outputs::file(const std::string& flag, const std::string& target) {
    if (target.empty() || target == "-") return target;
    const fs::path f = staged(flag, target, false);
    fs::create_directories(f.parent_path());
    return f.string();
}

void Outputs::commit() {
    throwIfInterrupted();
    const BlockStopSignals hold;
    // Every destination checked before the first file moves: a file cannot replace a folder,
    // nor go under a file.
    std::vector<std::pair<fs::path, fs::path>> moves;   // (staged file, destination)
    for (const Stage& s : stages_) {
        if (s.missing && !fs::exists(s.root)) continue;   // renamed whole below
        for (const auto& e : fs::recursive_directory_iterator(s.tmp)) {
            if (e.is_directory()) continue;
            const fs::path dest = s.root / e.path().lexically_relative(s.tmp);
            if (fs::is_directory(dest)) throw std::runtime_error(dest.string() + ": is a folder; the file cannot be written");
            for (fs::path d = dest.parent_path(); !d.empty() && d != s.root.parent_path(); d = d.parent_path())
                if (fs::exists(d) && !fs::is_directory(d))
                    throw std::runtime_error(dest.string() + ": '" + d.string() + "' is a file, not a folder");
            moves.emplace_back(e.path(), dest);
        }
    }
    for (const Stage& s : stages_)
        if (s.missing && !fs::exists(s.root)) fs::rename(s.tmp, s.root);
    for (const auto& [from, to] : moves) {
        fs::create_directories(to.parent_path());
        fs::rename(from, to);
    }
    committed_ = true;
    std::error_code ec;
    for (const Stage& s : stages_) fs::remove_all(s.tmp, ec);
}

Outputs::~Outputs() {
    if (committed_) return;
    std::error_code ec;
    for (const Stage& s : stages_) fs::remove_all(s.tmp, ec);
}

void checkTracePath(const std::string& trace) {
    const fs::path dir = fs::path(trace).parent_path();
    if (!dir.empty() && !fs::is_directory(dir))
        throw InputError("--trace: folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(trace)) throw InputError("--trace: '" + trace + "' is a folder, not a file");
}

void checkNotFolder(const std::string& flag, const std::string& path) {
    if (!path.empty() && path != "-" && fs::is_directory(path))
        throw InputError(flag + ": '" + path + "' is a folder; give a file name");
}

void checkOutFile(const std::string& flag, const std::string& path) {
    if (path.empty() || path == "-") return;
    checkNotFolder(flag, path);
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

void checkOutFolder(const std::string& outDir) {
    checkOutDir("-o", outDir);
    checkCreatableDir("-o", outDir.empty() ? "out" : outDir);
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
