// pst: the project's one command-line tool. Each subcommand is in testbench/tool/cmd/:
//   pst render SCENE      filtered, unfiltered, filter-width (and ground-truth) images + report
//   pst render SCENE --profile P   the same scene through the RTL (and golden) model of profile P
//   pst eval              texture block + fragment file -> f, grad_s f, w, filtered RGBA
//   pst fragments SCENE   the rasterizer's fragment stream as a fragment file
//   pst compare A B       mean / RMS / max / PSNR between two images, thresholds, difference image
//   pst regress           every scene x every profile through the RTL; non-zero exit on any mismatch
//   pst animate SCENE     the scene's time track: frames, videos, flicker against the ground truth
//   pst atlas SCENE       texture-atlas mode: the atlas filled by the models, the object texture-mapped
// Exit status: 0 success, 1 failure (including RTL mismatches), 2 bad input or usage.
#include <algorithm>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common.h"
#include "provenance.h"

using namespace pst;

namespace {

std::string versionText() {
    const BuildInfo& b = buildInfo();
    auto list = [](const std::vector<std::string>& v) {
        std::string s;
        for (const auto& n : v) s += (s.empty() ? "" : ", ") + n;
        return s.empty() ? std::string("none") : s;
    };
    return "pst " + b.version + "\ncommit " + b.commit + "\n" + b.verilator + "\ncompiler " + b.compiler +
           "\nverilated profiles: " + list(rtlProfiles()) + "\nwith assertions: " + list(rtlAssertedProfiles());
}

// Levenshtein distance, for the nearest subcommand to a typo.
size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

// The first argument, when it is neither an option nor a subcommand: named, with the nearest
// subcommand suggested (exit 2), before CLI11 would call it an unexpected argument.
bool unknownSubcommand(const CLI::App& app, int argc, char** argv) {
    if (argc < 2 || argv[1][0] == '-') return false;
    const std::string given = argv[1];
    std::string best;
    size_t bestD = SIZE_MAX;
    std::string names;
    for (const CLI::App* sc : app.get_subcommands({})) {
        if (sc->get_name() == given) return false;
        names += (names.empty() ? "" : ", ") + sc->get_name();
        const size_t d = editDistance(given, sc->get_name());
        if (d < bestD) bestD = d, best = sc->get_name();
    }
    std::cerr << "error: unknown subcommand '" << given << "'";
    if (bestD <= std::max<size_t>(2, given.size() / 3)) std::cerr << "; did you mean '" << best << "'?";
    std::cerr << "\nsubcommands: " << names << " (pst --help)\n";
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    setCommandLine(argc, argv);
    CLI::App app{"pst: cycle-level simulator of the Hart et al. 1999 procedural solid-texturing ASIC"};
    app.require_subcommand(1);
    app.option_defaults()->always_capture_default();
    app.set_version_flag("--version", versionText(), "Version, commit, Verilator and compiler versions");

    const std::vector<cli::Command> commands = {
        cli::registerRender(app),  cli::registerEval(app),    cli::registerRegress(app), cli::registerFragments(app),
        cli::registerCompare(app), cli::registerAnimate(app), cli::registerAtlas(app)};

    if (unknownSubcommand(app, argc, argv)) return 2;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    // SIGINT, SIGTERM: the run unwinds (its Outputs remove their temporary folders), then ends by
    // the signal (issue 41 part 2).
    cli::installInterruptHandlers();
    try {
        for (const cli::Command& c : commands)
            if (*c.app) return c.run();
    } catch (const Interrupted& e) {
        cli::endByInterrupt(e.signal);
    } catch (const InputError& e) {
        if (const int sig = gInterruptSignal.load()) cli::endByInterrupt(sig);
        // One line per error: a profile or scene file reports every error it has.
        std::istringstream lines(e.what());
        for (std::string line; std::getline(lines, line);) std::cerr << "error: " << line << "\n";
        return 2;
    } catch (const std::exception& e) {
        // A failure caused by the stop request (an interrupted write) is the stop.
        if (const int sig = gInterruptSignal.load()) cli::endByInterrupt(sig);
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 2;
}
