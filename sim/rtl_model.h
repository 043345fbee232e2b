// The verilated pipeline behind one interface, whatever the profile: register writes, a
// fragment stream in, pixels out, cycles counted. One verilated model per profile
// (Vpst_top_<profile>); makeRtlModel picks it by name.
#pragma once

#include <cstdint>
#include <array>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pipeline.h"

namespace pst {

// The run controller's settings (after lowRISC's VerilatorSimCtrl).
struct SimOptions {
    uint64_t seed = 1;              // random gaps and stalls
    uint64_t timeoutCycles = 0;     // 0 = derived from the work given (generous)
    std::string traceFile;          // FST waveform; empty = tracing off
    uint64_t traceStart = 0;        // first and last cycle traced
    uint64_t traceEnd = UINT64_MAX;
    double inputGapRate = 0.0;      // probability that the driver idles a cycle
    double outputStallRate = 0.0;   // probability that the monitor holds out_ready low
    int outputStallBurst = 0;       // > 1: a stall lasts 1..N cycles (uniform), so the skid
                                    // buffers fill and back-pressure reaches the serial stages
    uint64_t busyWriteAfter = 0;    // self-test: once this many fragments are in, the driver writes
                                    // a register while the pipeline is busy (a protocol violation
                                    // the RTL's RegWriteOnlyWhenIdle assertion catches); 0 = never
};

// An assertion of the RTL failed ($error or $fatal of a checker in rtl/sva/ or an inline one):
// the simulator printed its "%Error: ... Assertion failed in <module path>: ..." line on stdout
// and the model is not usable any more. A failed run like a mismatch, not a crash.
class RtlAssertionError : public std::runtime_error {
public:
    RtlAssertionError(const std::string& what, uint64_t cycle) : std::runtime_error(what), cycle(cycle) {}
    uint64_t cycle;              // the model's cycle at which it fired
    size_t pixelsOut = 0;        // pixels of the current run() already out when it fired
    size_t fragmentsIn = 0;      // fragments of the current run() taken by then
};

// What the octave-stage probes showed for one fragment (per active octave), for the
// scoreboard's unit localization.
struct ProbeFx {
    int64_t q = 0;
    std::vector<std::array<int, 3>> lat;
    std::vector<std::array<int64_t, 3>> frac;
    std::vector<int64_t> n;
    std::vector<std::array<int64_t, 3>> g;
};

class RtlModel {
public:
    virtual ~RtlModel() = default;
    virtual const std::string& profile() const = 0;
    virtual void reset() = 0;
    // Waits until the pipeline is idle, then writes one register per cycle.
    virtual void write(const std::vector<std::pair<uint16_t, uint32_t>>& writes) = 0;
    // Streams `frags` through the pipeline and returns the pixels in the order they came out.
    // Throws std::runtime_error on timeout, RtlAssertionError when an assertion fires (write()
    // too). Probes are recorded by tag when `probes` is given.
    virtual std::vector<PixelFx> run(const std::vector<FragmentFx>& frags, int activeOctaves,
                                     std::map<uint32_t, ProbeFx>* probes = nullptr) = 0;
    virtual uint64_t cycles() const = 0;       // since construction
    virtual uint64_t busyCycles() const = 0;   // cycles spent inside run()
    // The cycle (cycles()' count) at which each pixel of the last run() came out, in order: where
    // a mismatching pixel's waves are (regress --waves).
    virtual const std::vector<uint64_t>& outCycles() const { static const std::vector<uint64_t> none; return none; }
};

std::unique_ptr<RtlModel> makeRtlModel(const std::string& profile, const SimOptions& options = {});
// The profiles compiled into this build.
std::vector<std::string> rtlProfiles();
// Those verilated with every assertion (the checked flavour: the test profiles always, the named
// ones with -DPST_SIM_ASSERT=ON); the others fail only on a mismatch with the golden model.
std::vector<std::string> rtlAssertedProfiles();
// The profile file a verilated profile was built from ("" if `name` is not one of them): the
// registry's path relative to the source tree, resolved against sourceDir() at run time.
std::string rtlProfilePath(const std::string& name);
// That profile, parsed once per process (the registry's cache; every model of it shares it).
// Throws std::invalid_argument if `name` is not verilated in this build, InputError if the file
// does not parse.
const Profile& rtlProfile(const std::string& name);

}  // namespace pst
