// pst animate SCENE: the scene's time track: frames, videos, flicker against the ground truth
// (testbench/tool/animate), optionally through the hardware models.
#include <cstdio>
#include <memory>

#include <unistd.h>

#include "animate.h"
#include "common.h"

namespace pst::cli {

Command registerAnimate(CLI::App& app) {
    auto an = std::make_shared<AnimateArgs>();
    auto variants = std::make_shared<std::vector<std::string>>();
    auto flags = std::make_shared<std::pair<bool, bool>>(false, false);   // --no-video, -q
    auto* animate = app.add_subcommand("animate", "Render a scene's time track: PNG frames, videos, flicker.json");
    animate->add_option("scene", an->scene, "Scene file with an [animation] track")->required()->check(CLI::ExistingFile);
    animate->add_option("--frames", an->frames, "Frames (0: the scene's animation.frames)")->check(CLI::Range(1, 10000));
    animate->add_option("--size", an->size, "Square image size, overrides the scene's (0: the scene's)")->check(CLI::Range(1, 4096));
    animate->add_option("--truth", an->truth, "N x N ground truth per frame (the flicker metric needs it; 0: none)")->check(CLI::Range(1, 64));
    animate->add_option("--fps", an->fps, "Video frame rate (0: the scene's animation.fps)")->check(kFinite & CLI::Range(0.1, 240.0));
    addProfileOptions(animate, an->profiles, an->model, "Also through the hardware model(s) of these profiles, scoreboarded");
    animate->add_option("-o,--out", an->outDir, "Output folder (default out/anim/<scene name>)");
    animate->add_option("-j,--threads", an->threads, "Threads (0: all cores)")->check(CLI::Range(0, 256));
    animate->add_flag("--no-video", flags->first, "PNG frames and flicker.json only");
    addTextureOverrideOptions(animate, an->bandlimit, an->filter, an->widthCap);
    animate->add_option("--variants", *variants, "Also a reference stream per KIND[+BANDLIMIT] (every texture's filter "
                        "and bandlimit replaced), with its flicker")
        ->delimiter(',');
    animate->add_flag("-q,--quiet", flags->second, "No progress on stderr");
    auto trace = std::make_shared<std::string>();
    animate->add_option("--trace", *trace, "FST waveform of the RTL stream of frame --trace-frame (off unless given)");
    animate->add_option("--trace-frame", an->traceFrame, "The traced frame (0: the first; needed with --trace)")
        ->check(CLI::Range(0, 9999));
    animate->add_option("--trace-start", an->sim.traceStart, "First traced cycle (of the frame's stream)");
    animate->add_option("--trace-end", an->sim.traceEnd, "Last traced cycle (of the frame's stream)");
    return {animate, [an, variants, flags, animate, trace]() {
                if (an->profiles.empty()) refuseGiven(animate, {"--model"}, "needs --profile (without it no hardware model runs)");
                // --trace as pst render's, of one frame's stream.
                checkTraceOptions(animate, *trace, an->profiles, an->model, {"--trace-frame", "--trace-start", "--trace-end"});
                if (!trace->empty() && an->profiles.size() > 1)
                    throw InputError("--trace: one --profile only (one waveform of one RTL stream)");
                if (!trace->empty() && !animate->count("--trace-frame"))
                    throw InputError("--trace: needs --trace-frame K (the frame whose RTL stream is traced)");
                checkTraceWindow(an->sim);
                if (!trace->empty()) checkTracePath(*trace);
                checkNotInput("--trace", *trace, {an->scene});
                checkOutFolder(an->outDir);
                an->video = !flags->first;
                an->variants = parseVariants(*variants);
                AnimateArgs* a = an.get();
                an->loadProfile = [a](const std::string& n) { return profileByName(n, a->model == "rtl"); };
                // One line per frame and model (rewritten in place on a terminal).
                if (!flags->second)
                    an->progress = [name = fs::path(an->scene).stem().string(), tty = isatty(STDERR_FILENO)](
                                       const std::string& phase, double frac) {
                        std::fprintf(stderr, tty ? "\r%s: %-28s %5.1f%%" : "%s: %s %.1f%%\n", name.c_str(), phase.c_str(),
                                     100.0 * frac);
                        if (tty && frac >= 1.0) std::fprintf(stderr, "\n");
                    };
                // One output transaction: every frame, video and flicker.json, or none of them.
                Outputs outputs;
                an->writeDir = outputs.dir("-o", animateOutDir(*an));
                an->traceFile = outputs.file("--trace", *trace);
                const int rc = runAnimate(*an);
                outputs.commit();
                return rc;
            }};
}

}  // namespace pst::cli
