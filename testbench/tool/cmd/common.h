// What the pst subcommands (testbench/tool/cmd/*.cpp) share: the registration interface, the
// hardware-model options, profiles by name, progress on stderr, output files and checks.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "hwrender.h"
#include "input_error.h"
#include "interrupt.h"
#include "render.h"
#include "rtl_model.h"
#include "scene.h"

namespace pst::cli {

namespace fs = std::filesystem;

// A subcommand: its CLI11 app and what runs when it was given (returns the exit status:
// 0 success, 1 failure, 2 bad input; throws InputError for bad input).
struct Command {
    CLI::App* app = nullptr;
    std::function<int()> run;
};

Command registerRender(CLI::App& app);
Command registerEval(CLI::App& app);
Command registerRegress(CLI::App& app);
Command registerFragments(CLI::App& app);
Command registerCompare(CLI::App& app);
Command registerAnimate(CLI::App& app);
Command registerAtlas(CLI::App& app);

// Hardware-model options shared by render --profile, regress, eval --model and atlas --profile.
struct HwArgs {
    std::vector<std::string> profiles;
    std::string model = "rtl";      // rtl | golden
    SimOptions sim;
    std::string trace;
    std::string html;               // render --profile --html: the runs' page
};

// --sim-seed, --gap-rate, --stall-rate, --timeout into hw.sim.
void addSimOptions(CLI::App* sc, HwArgs& hw);
extern const std::vector<std::string> kSimOptions;
// A flag that would do nothing in this mode is refused, not ignored (41 part 4): the first of
// `names` given on the command line, with `why`.
void refuseGiven(const CLI::App* app, const std::vector<std::string>& names, const std::string& why);
// The hardware options of a command whose models run only with --profile: --model and the
// simulation options need --profile, the simulation options need --model rtl.
void refuseHardwareOptionsWithoutModel(const CLI::App* app, const HwArgs& hw);
// The help text of --profile: `what`, then the profiles this build verilated (its registry).
std::string profileHelp(const std::string& what);

extern const std::vector<std::string> kBandlimitNames, kFilterNames;
// CLI11's Range lets NaN through (every comparison with NaN is false).
extern const CLI::Validator kFinite;

// --profile and --model (rtl or golden): the hardware model(s) a command also runs; `what` begins
// --profile's help.
void addProfileOptions(CLI::App* sc, std::vector<std::string>& profiles, std::string& model, const std::string& what);
// --bandlimit, --filter and --width-cap: every texture's, overriding the scene's (overrideTextures).
void addTextureOverrideOptions(CLI::App* sc, std::string& bandlimit, std::string& filter, std::string& widthCap);
// --trace and the options of its window (`window`: --trace-start, --trace-end, ...): the waves are
// the RTL's, so they need --profile and --model rtl, and the window needs --trace FILE. Returns
// whether any of them was given.
bool checkTraceOptions(const CLI::App* sc, const std::string& trace, const std::vector<std::string>& profiles,
                       const std::string& model, const std::vector<std::string>& window);
// The traced window: --trace-start not after --trace-end.
void checkTraceWindow(const SimOptions& sim);

std::vector<FilterVariant> parseVariants(const std::vector<std::string>& specs);
// --bandlimit and --filter: every texture of the scene gets them (a bandlimit a texture cannot
// take is refused).
void overrideTextures(Scene& scene, const std::string& bandlimit, const std::string& filter,
                      const std::string& widthCap = "");
// Every variant's bandlimit must suit every texture of the scene.
void checkVariants(const Scene& scene, const std::vector<FilterVariant>& variants);

// Progress on stderr: one rewritten line on a terminal, a line per phase otherwise.
std::function<void(const std::string&, double)> progressPrinter(const std::string& name, bool quiet);

// Progress of a run of `total` steps with an ETA on stderr (rewritten in place on a terminal,
// a line per step otherwise); silent when quiet.
class EtaProgress {
public:
    EtaProgress(std::string name, size_t total, bool quiet);
    void step(const std::string& what);   // one more step done
    void finish();

private:
    std::string name_;
    size_t total_, done_ = 0;
    double lastLine_ = 0;   // seconds at the last line printed
    bool quiet_, tty_;
    std::chrono::steady_clock::time_point t0_;
};

// The HTML page of hardware runs, written by scripts/report.py to `page` (a path in the run's
// Outputs; `shown` is the path the user gave, for the messages). Throws when it fails (the run's
// outputs are then discarded).
void writeHtmlPage(const std::string& page, const std::string& shown, std::vector<std::string> args);

// A verilated profile by its name (rtl/configs or PST_EXTRA_PROFILE_DIR), else a name in
// rtl/configs or a profile file. For the RTL (rtl = true) the profile must have a verilated
// model in this build, and the same values as the file that model was built from. The refusal
// suggests --model golden only where the command has that option (hasModelOption).
Profile profileByName(const std::string& name, bool rtl = false, bool hasModelOption = true);

// One output transaction per run (issue 41 part 2): outputs are whole or absent. Every file of
// the run is written into a temporary folder on the target's filesystem -- `.NAME.pst-tmp-PID`
// beside a folder that does not exist yet (the first missing one on the way), `.pst-tmp-PID`
// inside one that does -- and commit() moves it into place: the whole folder by one rename when
// the target did not exist, else file by file (each an atomic rename; files of the target that
// this run did not write are kept). Not committed (an error, a refused input, a failed report
// step, SIGINT or SIGTERM: interrupt.h), the destructor removes the temporary folders.
class Outputs {
public:
    Outputs() = default;
    Outputs(const Outputs&) = delete;
    Outputs& operator=(const Outputs&) = delete;
    ~Outputs();

    // Where to write the folder `target` (given with `flag`): a temporary folder, made now, so a
    // folder that cannot be made is refused here (InputError, with the path and the reason)
    // before any work.
    std::string dir(const std::string& flag, const std::string& target);
    // Where to write the file `target` ("" and "-", stdout, are returned as they are).
    std::string file(const std::string& flag, const std::string& target);
    // Moves every file into place (SIGINT and SIGTERM held back meanwhile). A destination that
    // is a folder, or under a file, fails the commit before anything is moved.
    void commit();
    // `--staged TMP=FINAL` for each temporary folder: what a step that reads the staged files
    // before the commit (the HTML page) needs to name where they will be.
    std::vector<std::string> stagedArgs() const;

private:
    struct Stage {
        fs::path root;   // the folder the files go to (made by the commit when missing)
        fs::path tmp;    // the temporary folder holding them
        bool missing;    // root did not exist: the commit renames tmp to root
    };
    fs::path staged(const std::string& flag, const std::string& target, bool isDir);
    std::vector<Stage> stages_;
    bool committed_ = false;
};

// The last step of a run with an optional HTML page (`shown`, the path the user gave; none when
// empty): the page (writeHtmlPage, from `args` and the staged outputs), the commit, then where
// the page is on stdout.
void commitWithPage(Outputs& outputs, const std::string& page, const std::string& shown, std::vector<std::string> args);

// SIGINT, SIGTERM and SIGHUP record the signal (interrupt.h) for the run to unwind; a second one ends the
// process at once.
void installInterruptHandlers();
// After a run stopped by `sig` unwound (its outputs removed): says so and ends the process by
// the same signal (exit status 128 + sig in a shell).
[[noreturn]] void endByInterrupt(int sig);

// spawnAndWait (interrupt.h) runs a child (report.py, ffmpeg); the caller's check
// (throwIfInterrupted) ends the run on a stop request.

// Fails (InputError) unless a trace file can be written: its folder exists.
void checkTracePath(const std::string& trace);
// An output file given with -o must not be an existing folder, and its folder must exist and be
// writable.
void checkOutFile(const std::string& flag, const std::string& path);
// An output file whose folder may be made (--html) must not be an existing folder.
void checkNotFolder(const std::string& flag, const std::string& path);
// An output folder given with -o must not be a file.
void checkOutDir(const std::string& flag, const std::string& path);
// The output folder of -o (default: under out/) as render, animate and atlas take it: not a file,
// and creatable.
void checkOutFolder(const std::string& outDir);

// An output that is one of the run's inputs (the same file, std::filesystem::equivalent) is
// refused before any work: it would overwrite the input.
void checkNotInput(const std::string& flag, const std::string& out, const std::vector<std::string>& inputs);

// An output folder must exist as a writable folder or be creatable: checked before any work,
// with the path and the reason (41 part 1).
void checkCreatableDir(const std::string& flag, const std::string& dir);
// The folder an output file goes to (its parent) the same way.
void checkCreatableFileDir(const std::string& flag, const std::string& file);

// Whether this build verilated `profile` with its assertions (the checked flavour).
bool asserted(const std::string& profile);

// summary.json of one hardware run (without provenance).
nlohmann::json hwJson(const std::string& scene, const Profile& p, const std::string& model,
                      const HwRenderResult& r, int w, int h);

// The first texture of the scene's objects that profile p cannot run (hardwareUnsupported), or "".
std::string unsupportedTexture(const Scene& scene, const Profile& p);

}  // namespace pst::cli
