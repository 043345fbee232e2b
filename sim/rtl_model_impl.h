// The Verilator harness of pst_top, templated on the verilated class of one profile:
//   Dut      thin wrapper: clock, reset, tick, FST tracing in a cycle window
//   Driver   offers fragments on the valid/ready input, with random idle cycles
//   Monitor  takes pixels from the output, with random back-pressure; samples the probes
// (after Verilator's examples and lowRISC's VerilatorSimCtrl / dv drivers and monitors).
#pragma once

#include <algorithm>
#include <array>
#include <deque>
#include <random>
#include <stdexcept>
#include <string>

#include <verilated.h>
#include <verilated_fst_c.h>
#if VM_COVERAGE
#include <atomic>
#include <cstdlib>
#include <unistd.h>
#include <verilated_cov.h>
#endif

#include "contract.h"
#include "fixed.h"
#include "rtl_model.h"
#include "verilated_port.h"

namespace pst {

template <typename Top>
class RtlModelImpl final : public RtlModel {
public:
    RtlModelImpl(std::string profileName, const Profile& prof, const SimOptions& opt)
        : name_(std::move(profileName)), p_(prof), opt_(opt), rng_(opt.seed) {
        ctx_.randReset(0);
        // A failed assertion ($error, $fatal) sets gotError instead of aborting the process;
        // check() turns it into an RtlAssertionError, so the caller records a failed run.
        ctx_.fatalOnError(false);
        ctx_.traceEverOn(!opt_.traceFile.empty());
        top_ = std::make_unique<Top>(&ctx_, "pst_top");
        if (!opt_.traceFile.empty()) {
            trace_ = std::make_unique<VerilatedFstC>();
            top_->trace(trace_.get(), 99);
        }
        reset();
    }
    ~RtlModelImpl() override {
        if (trace_) trace_->close();
        top_->final();
#if VM_COVERAGE
        // Coverage build (-DPST_COVERAGE=ON): one file per model instance, merged by
        // scripts/coverage.sh with verilator_coverage.
        if (const char* dir = std::getenv("PST_COVERAGE_DIR")) {
            static std::atomic<int> serial{0};
            const std::string path = std::string(dir) + "/" + name_ + "_" + std::to_string(::getpid()) + "_" +
                                     std::to_string(serial++) + ".dat";
            ctx_.coveragep()->write(path.c_str());
        }
#endif
    }

    const std::string& profile() const override { return name_; }
    uint64_t cycles() const override { return cycle_; }
    uint64_t busyCycles() const override { return busy_; }
    const std::vector<uint64_t>& outCycles() const override { return outCycles_; }

    void reset() override {
        current();
        top_->clk_i = 0;
        top_->rst_ni = 0;
        top_->reg_we_i = 0;
        top_->frag_valid_i = 0;
        top_->out_ready_i = 0;
        for (int i = 0; i < 3; ++i) tick();
        top_->rst_ni = 1;
        tick();
    }

    void write(const std::vector<std::pair<uint16_t, uint32_t>>& writes) override {
        current();
        waitIdle();
        for (const auto& [addr, data] : writes) {
            top_->reg_we_i = 1;
            top_->reg_addr_i = addr;
            top_->reg_wdata_i = data;
            tick();
        }
        top_->reg_we_i = 0;
    }

    std::vector<PixelFx> run(const std::vector<FragmentFx>& frags, int activeOctaves,
                             std::map<uint32_t, ProbeFx>* probes) override {
        current();
        std::vector<PixelFx> out;
        out.reserve(frags.size());
        outCycles_.clear();
        outCycles_.reserve(frags.size());
        size_t next = 0;
        try {
            stream(frags, activeOctaves, probes, out, next);
        } catch (RtlAssertionError& e) {
            e.pixelsOut = out.size();
            e.fragmentsIn = next;
            throw;
        }
        return out;
    }

private:
    // Fragments in, pixels out (`next`: fragments taken so far).
    void stream(const std::vector<FragmentFx>& frags, int activeOctaves, std::map<uint32_t, ProbeFx>* probes,
                std::vector<PixelFx>& out, size_t& next) {
        const uint64_t start = cycle_;
        const uint64_t limit = opt_.timeoutCycles ? opt_.timeoutCycles
                                                  : 1000 + 64 * uint64_t(frags.size()) * p_.cyclesPerPixel();
        std::bernoulli_distribution gap(opt_.inputGapRate), stall(opt_.outputStallRate);
        std::uniform_int_distribution<int> burst(1, std::max(1, opt_.outputStallBurst));
        int stallLeft = 0;   // cycles of the current stall burst still to come
        bool offering = false;
        while (out.size() < frags.size()) {
            if (cycle_ - start > limit)
                throw std::runtime_error("rtl " + name_ + ": timeout after " + std::to_string(limit) +
                                         " cycles with " + std::to_string(out.size()) + " of " +
                                         std::to_string(frags.size()) + " pixels out");
            // Driver: a fragment once offered stays offered until it is taken.
            if (!offering && next < frags.size() && !gap(rng_)) {
                drive(frags[next]);
                offering = true;
            }
            top_->frag_valid_i = offering;
            // Monitor: random back-pressure (a burst of 1..outputStallBurst cycles per stall).
            bool ready = true;
            if (stallLeft > 0) {
                --stallLeft;
                ready = false;
            } else if (stall(rng_)) {
                ready = false;
                if (opt_.outputStallBurst > 1) stallLeft = burst(rng_) - 1;
            }
            top_->out_ready_i = ready;
            // The low phase: the combinational outputs (frag_ready_o, out_valid_o) of this
            // cycle's inputs. Two evaluations per cycle, this one and the rising edge's
            // (every eval() also re-evaluates the input-driven logic: a third, a separate
            // falling-edge eval, cost reduced 11 % of its time).
            top_->clk_i = 0;
            top_->eval();
            dump(2 * cycle_);
            check();
            const bool fragTaken = offering && top_->frag_ready_o;
            const bool pixelTaken = top_->out_valid_o && top_->out_ready_i;
            if (pixelTaken) {
                out.push_back(sample());
                outCycles_.push_back(cycle_);
            }
            if (probes && top_->probe_valid_o) sampleProbes(*probes, activeOctaves);
            if (probes && top_->probe_q_valid_o)
                (*probes)[top_->probe_q_tag_o].q = port::getSigned(top_->probe_q_o, 0, p_.f.width());
            // Self-test (SimOptions::busyWriteAfter): one register write while fragments are in flight.
            const bool violate = opt_.busyWriteAfter && !violated_ && taken_ >= opt_.busyWriteAfter && !top_->idle_o;
            if (violate) {
                top_->reg_we_i = 1;
                top_->reg_addr_i = 0;
                top_->reg_wdata_i = 0;
                violated_ = true;
            }
            if (fragTaken) {
                offering = false;
                ++next;
                ++taken_;
            }
            rise();
            if (violate) top_->reg_we_i = 0;
        }
        top_->frag_valid_i = 0;
        top_->out_ready_i = 0;
        busy_ += cycle_ - start;
    }

    // Verilator reports a failed assertion to the thread's current context: this model's.
    void current() { Verilated::threadContextp(&ctx_); }
    void check() {
        if (VL_UNLIKELY(ctx_.gotError()))
            throw RtlAssertionError("rtl " + name_ + ": an RTL assertion failed at cycle " + std::to_string(cycle_) +
                                        " (the simulator's %Error line names the checker and the assertion)",
                                    cycle_);
    }
    void tick() {
        top_->clk_i = 0;
        top_->eval();
        dump(2 * cycle_);
        check();
        rise();
    }
    // The rising edge (the low phase evaluated before it).
    void rise() {
        top_->clk_i = 1;
        top_->eval();
        dump(2 * cycle_ + 1);   // a failing edge is in the waves
        check();
        ++cycle_;
        ctx_.timeInc(1);
    }
    void dump(uint64_t t) {
        if (trace_ && cycle_ >= opt_.traceStart && cycle_ <= opt_.traceEnd) {
            if (!traceOpen_) {
                trace_->open(opt_.traceFile.c_str());
                traceOpen_ = true;
            }
            trace_->dump(t);
        }
    }
    void waitIdle() {
        for (int i = 0; i < 100000 && !top_->idle_o; ++i) {
            top_->out_ready_i = 1;
            tick();
        }
        if (!top_->idle_o) throw std::runtime_error("rtl " + name_ + ": pipeline does not drain");
    }

    void drive(const FragmentFx& f) {
        const int cw = p_.coord.width(), jw = p_.jacobian.width();
        top_->frag_tag_i = f.tag;
        for (int k = 0; k < 3; ++k) port::set(top_->frag_s_i, k * cw, cw, uint64_t(f.s[k]));
        for (int k = 0; k < 6; ++k) port::set(top_->frag_j_i, k * jw, jw, uint64_t(f.j[k]));
    }

    PixelFx sample() const {
        const int fw = p_.f.width(), gw = p_.grad.width();
        const int ww = p_.widthBits();
        PixelFx px;
        px.tag = top_->out_tag_o;
        px.rgba = uint32_t(port::get(top_->out_rgba_o, 0, 4 * p_.colourBits));
        px.f = port::getSigned(top_->out_f_o, 0, fw);
        for (int k = 0; k < 3; ++k) px.grad[k] = port::getSigned(top_->out_grad_o, k * gw, gw);
        px.w = int64_t(port::get(top_->out_w_o, 0, ww));
        return px;
    }

    void sampleProbes(std::map<uint32_t, ProbeFx>& probes, int active) const {
        namespace c = contract;
        const int lf = p_.noiseLatticeFrac, nw = c::kNoiseIntBits + p_.noiseOutFrac,
                  ngw = c::kNoiseGradIntBits + p_.noiseOutFrac;
        ProbeFx& pr = probes[top_->probe_tag_o];
        const int pass = int(top_->probe_pass_o);
        const int n = std::min(active, p_.octaves);
        if (int(pr.n.size()) < n) {
            pr.lat.resize(n);
            pr.frac.resize(n);
            pr.n.resize(n);
            pr.g.resize(n);
        }
        for (int u = 0; u < p_.noiseUnits; ++u) {
            const int i = pass * p_.noiseUnits + u;
            if (i >= n) break;
            for (int k = 0; k < 3; ++k) {
                pr.lat[i][k] = int(port::get(top_->probe_lat_o, u * c::kLatticeWidth + c::kLatticeBits * k, c::kLatticeBits));
                pr.frac[i][k] = int64_t(port::get(top_->probe_frac_o, (u * 3 + k) * lf, lf));
                pr.g[i][k] = port::getSigned(top_->probe_g_o, (u * 3 + k) * ngw, ngw);
            }
            pr.n[i] = port::getSigned(top_->probe_n_o, u * nw, nw);
        }
    }

    std::string name_;
    Profile p_;
    SimOptions opt_;
    std::mt19937_64 rng_;
    VerilatedContext ctx_;
    std::unique_ptr<Top> top_;
    std::unique_ptr<VerilatedFstC> trace_;
    bool traceOpen_ = false;
    uint64_t cycle_ = 0;
    std::vector<uint64_t> outCycles_;   // of the last run()
    uint64_t busy_ = 0;
    uint64_t taken_ = 0;          // fragments taken since construction
    bool violated_ = false;       // the busyWriteAfter self-test has written
};

}  // namespace pst
