// `pst animate`: a scene's time track rendered frame by frame through the reference (and
// optionally golden + RTL, scoreboarded), PNG frames, a browser-playable video per stream
// (ffmpeg, VP9 webm), and the flicker metric against the ground truth (flicker.json).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "render.h"
#include "rtl_model.h"

namespace pst {

struct AnimateArgs {
    std::string scene, outDir;   // outDir default: animateOutDir
    // Where the files are written while the run lasts (the CLI's output transaction: a temporary
    // folder moved to outDir when the run succeeds); "": outDir itself.
    std::string writeDir;
    int frames = 0;              // 0: the scene's [animation] frames
    int size = 0;                // square size; 0: the scene's
    int truth = 0;               // n x n ground truth per frame (needed for the flicker metric)
    int threads = 0;
    double fps = 0;              // 0: the scene's [animation] fps
    bool video = true;
    std::string bandlimit;       // "": as the scene says; else every texture's (parseBandlimit)
    std::string filter;          // "": as the scene says; else every texture's filter kind
    std::string widthCap;        // "": as the scene says; "on" / "off": every texture's width cap
    std::vector<FilterVariant> variants;  // extra reference streams (named by the variant)
    std::vector<std::string> profiles;
    std::string model = "rtl";   // rtl | golden
    SimOptions sim;              // sim.traceStart/traceEnd: the window of traceFile (cycles of the frame's stream)
    // FST waveform of the RTL stream of frame traceFrame (the first profile's; "": none). Cycles
    // count from that frame's stream start (each frame runs a fresh RTL model), as in pst render.
    std::string traceFile;
    int traceFrame = 0;
    std::function<Profile(const std::string&)> loadProfile;
    std::function<void(const std::string&, double)> progress;   // (phase, fraction of the whole run)
};

// Temporal RMS error of a stream against the ground truth between frames k-1 and k: the RMS over
// pixels and RGB of (X_k - X_{k-1}) - (T_k - T_{k-1}). What the viewer sees as flicker is the
// part of the change from frame to frame that the true (area-averaged) image does not have.
double temporalRms(const Image& prev, const Image& cur, const Image& truthPrev, const Image& truthCur);

// The output folder: outDir, or out/anim/<scene name>.
std::string animateOutDir(const AnimateArgs& args);

// Returns the exit status: 0, or 1 on any RTL mismatch. A failed video throws (no output is
// whole without it); so does a stop request (SIGINT, SIGTERM: interrupt.h), between frames.
int runAnimate(const AnimateArgs& args);

}  // namespace pst
