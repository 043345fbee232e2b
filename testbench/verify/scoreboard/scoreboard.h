// The scoreboard: every pixel the RTL puts out is checked against the golden model, bit for
// bit, in order (after Vortex's unit-test scoreboards: queued by ID, first mismatches printed
// with their inputs). A mismatch names the first unit (docs/HARDWARE.md "Units") whose value
// differs, using the octave-stage probes of the RTL and the golden model's unit trace.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "pipeline.h"
#include "rtl_model.h"

namespace pst {

struct Mismatch {
    FragmentFx input;
    PixelFx expected, got;
    Unit unit = Unit::Count;      // first unit that differs
    std::string detail;           // the differing values
};

class Scoreboard {
public:
    explicit Scoreboard(const Profile& p, size_t maxReports = 8) : p_(p), maxReports_(maxReports) {}

    // The golden result for a fragment about to be sent (queued in order).
    void expect(const FragmentFx& in, const PixelFx& golden, const UnitTrace& trace);
    // A pixel from the RTL; `probe` is what the octave-stage probes showed for its tag.
    void observe(const PixelFx& got, const ProbeFx* probe);
    // Everything still queued is lost.
    void finish();

    size_t checked() const { return checked_; }
    size_t mismatches() const { return mismatches_; }
    size_t lost() const { return lost_; }
    size_t unexpected() const { return unexpected_; }   // duplicated, reordered or unknown tags
    bool passed() const { return mismatches_ == 0 && lost_ == 0 && unexpected_ == 0; }
    const std::vector<Mismatch>& reports() const { return reports_; }
    // Counts per first-differing unit.
    const std::map<Unit, size_t>& byUnit() const { return byUnit_; }
    std::string summary() const;

private:
    struct Pending {
        FragmentFx in;
        PixelFx golden;
        UnitTrace trace;
    };
    // The first unit whose value differs, Unit::Count if none.
    Unit locate(const Pending& e, const PixelFx& got, const ProbeFx* probe, std::string* detail) const;

    Profile p_;
    size_t maxReports_;
    std::deque<Pending> queue_;
    std::vector<Mismatch> reports_;
    std::map<Unit, size_t> byUnit_;
    size_t checked_ = 0, mismatches_ = 0, lost_ = 0, unexpected_ = 0;
};

}  // namespace pst
