// `pst animate`: frames, videos and flicker of a scene's time track.
#include "animate.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "driver.h"
#include "hwrender.h"
#include "imageio.h"
#include "interrupt.h"
#include "provenance.h"
#include "scene.h"


namespace fs = std::filesystem;

namespace pst {
namespace {

bool onPath(const std::string& exe) {
    const char* p = std::getenv("PATH");
    std::stringstream ss(p ? p : "");
    std::string dir;
    while (std::getline(ss, dir, ':'))
        if (!dir.empty() && access((fs::path(dir) / exe).c_str(), X_OK) == 0) return true;
    return false;
}

std::string frameName(int k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "frame_%04d.png", k);
    return buf;
}

// One image stream of the sequence: frames on disk, its error against the truth per frame.
struct Stream {
    std::string name;
    Image prev;
    std::vector<double> rms;       // vs the truth, per frame
    std::vector<double> temporal;  // per frame k >= 1
    size_t mismatches = 0;         // hardware streams: scoreboard mismatches over all frames
    bool hardware = false;
    bool variant = false;          // a --variants reference stream
};

double rmsOf(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    return v.empty() ? 0.0 : std::sqrt(s / double(v.size()));
}
double meanOf(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
}

}  // namespace

double temporalRms(const Image& prev, const Image& cur, const Image& truthPrev, const Image& truthCur) {
    const size_t n = size_t(cur.width) * cur.height;
    double s = 0;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const size_t j = i * 4 + c;
            const double d = (double(cur.data[j]) - prev.data[j]) - (double(truthCur.data[j]) - truthPrev.data[j]);
            s += d * d;
        }
    return n ? std::sqrt(s / double(3 * n)) : 0.0;
}

std::string animateOutDir(const AnimateArgs& a) {
    return a.outDir.empty() ? (fs::path("out") / "anim" / fs::path(a.scene).stem()).string() : a.outDir;
}

int runAnimate(const AnimateArgs& a) {
    // --bandlimit and --filter: every texture of every frame.
    auto overrideTextures = [&a](Scene& sc) {
        for (auto& t : sc.textures) {
            if (!a.bandlimit.empty()) {
                parseBandlimit(a.bandlimit, &t.bandlimit);
                if (std::string why = bandlimitUnsupported(t, t.bandlimit); !why.empty())
                    throw InputError("--bandlimit: " + a.bandlimit + ": texture '" + t.name + "': " + why);
            }
            if (!a.filter.empty()) parseFilterKind(a.filter, &t.filter);
            if (!a.widthCap.empty()) {
                t.widthCap = a.widthCap == "on";
                t.widthCapSource.clear();
            }
        }
    };
    Scene still = loadScene(a.scene, a.size, a.size);
    overrideTextures(still);
    for (const auto& v : a.variants)
        for (const auto& t : still.textures)
            if (std::string why = bandlimitUnsupported(t, v.bandlimit); !why.empty())
                throw InputError("--variants: " + v.name + ": texture '" + t.name + "': " + why);
    const std::string stem = fs::path(a.scene).stem().string();
    if (still.animation.empty())
        throw InputError(a.scene + ": animation: the scene has no [animation] time track (scenes/README.md)");
    const int frames = a.frames ? a.frames : still.animation.frames;
    if (frames < 1) throw InputError("--frames: the scene's [animation] gives no frames; give --frames N");
    const double fps = a.fps > 0 ? a.fps : still.animation.fps;
    if (a.video && !onPath("ffmpeg"))
        throw InputError("--video: ffmpeg is not on the PATH (scripts/setup.sh installs it; --no-video writes the frames only)");
    std::vector<Profile> profiles;
    for (const auto& name : a.profiles) {
        profiles.push_back(a.loadProfile(name));
        for (const auto& o : still.objects)
            if (std::string why = hardwareUnsupported(profiles.back(), still.textures[o.texture]); !why.empty())
                throw InputError(why);
    }
    if (!a.traceFile.empty()) {
        if (profiles.size() != 1 || a.model != "rtl")
            throw InputError("--trace: needs one --profile and --model rtl (one waveform of one RTL stream)");
        if (a.traceFrame < 0 || a.traceFrame >= frames)
            throw InputError("--trace-frame: " + std::to_string(a.traceFrame) + " is not a frame of this run (0.." +
                             std::to_string(frames - 1) + ")");
    }
    const fs::path shown = animateOutDir(a), dir = a.writeDir.empty() ? shown : fs::path(a.writeDir);

    std::vector<Stream> streams{{"filtered"}, {"unfiltered"}};
    for (const auto& p : profiles) {
        streams.push_back({p.name});
        streams.back().hardware = true;
    }
    for (const auto& v : a.variants) {
        for (const auto& st : streams)
            if (st.name == v.name) throw InputError("--variants: '" + v.name + "' is also a stream's name");
        streams.push_back({v.name});
        streams.back().variant = true;
    }
    std::vector<std::string> dirs;
    for (const auto& s : streams) dirs.push_back(s.name);
    if (a.truth > 0) dirs.push_back("truth");
    for (const auto& d : dirs) fs::create_directories(dir / d);

    Image truthPrev;
    bool passed = true;
    std::vector<std::string> notes;
    const auto t0 = std::chrono::steady_clock::now();
    const double steps = double(frames) * (1 + profiles.size());
    for (int k = 0; k < frames; ++k) {
        throwIfInterrupted();   // SIGINT, SIGTERM: between frames (and rows, in render)
        const double t = frames > 1 ? double(k) / double(frames - 1) : 0.0;
        Scene scene = loadSceneAt(a.scene, t, a.size, a.size);
        overrideTextures(scene);
        RenderOptions ro;
        ro.truthSamples = a.truth;
        ro.threads = a.threads;
        ro.variants = a.variants;
        RenderResult r = render(scene, ro);
        std::vector<Image> current{r.filtered, r.unfiltered};
        if (a.progress) a.progress("frame " + std::to_string(k + 1) + "/" + std::to_string(frames) + " reference",
                                   (k * (1 + profiles.size()) + 1) / steps);
        for (size_t pi = 0; pi < profiles.size(); ++pi) {
            const Profile& p = profiles[pi];
            std::unique_ptr<RtlModel> rtl;
            if (a.model == "rtl") {
                SimOptions so = a.sim;
                so.traceFile = (pi == 0 && k == a.traceFrame) ? a.traceFile : std::string();
                rtl = makeRtlModel(p.name, so);
            }
            HwRenderResult h = renderHardware(scene, p, rtl.get());
            Stream& st = streams[2 + pi];
            st.mismatches += h.mismatches;
            if (rtl && !h.passed) {
                passed = false;
                std::cout << stem << " frame " << k << " [" << p.name << "]: " << h.scoreboard;
            }
            for (const auto& n : h.notes)
                if (std::find(notes.begin(), notes.end(), p.name + ": " + n) == notes.end()) notes.push_back(p.name + ": " + n);
            current.push_back(std::move(h.hardware));
            if (a.progress) a.progress("frame " + std::to_string(k + 1) + "/" + std::to_string(frames) + " " + p.name,
                                       (k * (1 + profiles.size()) + 2 + pi) / steps);
        }
        for (auto& img : r.variants) current.push_back(std::move(img));
        for (size_t si = 0; si < streams.size(); ++si) {
            Stream& st = streams[si];
            writeImage(current[si], (dir / st.name / frameName(k)).string());
            if (a.truth > 0) {
                st.rms.push_back(compareRgb(current[si], r.truth).rmsError);
                if (k > 0) st.temporal.push_back(temporalRms(st.prev, current[si], truthPrev, r.truth));
            }
            st.prev = std::move(current[si]);
        }
        if (a.truth > 0) {
            writeImage(r.truth, (dir / "truth" / frameName(k)).string());
            truthPrev = std::move(r.truth);
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    int rc = passed ? 0 : 1;
    nlohmann::json j;
    j["scene"] = a.scene;
    j["title"] = still.title;
    j["bandlimit"] = a.bandlimit;
    j["width_cap"] = a.widthCap;
    j["filter"] = a.filter;
    j["frames"] = frames;
    j["fps"] = fps;
    j["width"] = still.camera.width;
    j["height"] = still.camera.height;
    j["truth_samples"] = a.truth * a.truth;
    j["seconds"] = seconds;
    j["model"] = profiles.empty() ? "" : a.model;
    j["passed"] = passed;
    j["notes"] = notes;
    j["metric"] = "temporal RMS error: per frame k >= 1, RMS over pixels and RGB of "
                  "(X_k - X_{k-1}) - (T_k - T_{k-1}), T the ground truth; flicker = RMS over frames";
    nlohmann::json sj = nlohmann::json::object();
    for (const auto& st : streams) {
        nlohmann::json e;
        e["hardware"] = st.hardware;
        if (st.variant) e["variant"] = true;
        if (st.hardware) e["mismatches"] = st.mismatches;
        if (a.truth > 0) {
            e["rms_vs_truth"] = st.rms;
            e["temporal_rms"] = st.temporal;
            e["mean_rms_vs_truth"] = meanOf(st.rms);
            e["flicker"] = rmsOf(st.temporal);
        }
        sj[st.name] = e;
    }
    j["streams"] = sj;
    std::ostringstream line;
    line << stem << ": " << frames << " frames " << still.camera.width << "x" << still.camera.height << ", " << seconds
         << " s";
    if (a.truth > 0) {
        const double ff = rmsOf(streams[0].temporal), fu = rmsOf(streams[1].temporal);
        j["flicker_ratio_unfiltered_over_filtered"] = ff > 0 ? fu / ff : 0.0;
        line << ", flicker (temporal RMS vs truth): filtered " << ff << ", unfiltered " << fu;
        if (ff > 0) line << " (" << fu / ff << "x)";
        for (size_t si = 2; si < streams.size(); ++si) line << ", " << streams[si].name << " " << rmsOf(streams[si].temporal);
    }
    for (size_t si = 2; si < streams.size(); ++si)
        if (streams[si].hardware) line << ", " << streams[si].name << " " << streams[si].mismatches << " mismatches";

    if (a.video) {
        for (const auto& d : dirs) {
            const std::string out = (dir / (d + ".webm")).string();
            char rate[32];
            std::snprintf(rate, sizeof rate, "%g", fps);
            // VP9 in WebM with 4:2:0 chroma: what every current browser plays. yuv420p needs even sizes.
            if (!spawnAndWait({"ffmpeg", "-y", "-loglevel", "error", "-framerate", rate, "-i",
                        (dir / d / "frame_%04d.png").string(), "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                        "-c:v", "libvpx-vp9", "-pix_fmt", "yuv420p", "-b:v", "0", "-crf", "30",
                        "-deadline", "realtime", "-cpu-used", "8", "-row-mt", "1", out})) {
                throwIfInterrupted();
                throw std::runtime_error("ffmpeg did not write " + (shown / (d + ".webm")).string() +
                                         " (nothing of this run is written)");
            } else {
                j["videos"][d] = d + ".webm";
            }
        }
    }
    writeTextFile((dir / "flicker.json").string(), withProvenance(j).dump(2) + "\n");
    std::cout << line.str() << " -> " << shown.string() << "\n";
    for (const auto& n : notes) std::cout << "  note: " << n << "\n";
    return rc;
}

}  // namespace pst
