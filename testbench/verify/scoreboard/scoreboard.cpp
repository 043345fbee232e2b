#include "scoreboard.h"

#include <cstdio>
#include <sstream>

namespace pst {

void Scoreboard::expect(const FragmentFx& in, const PixelFx& golden, const UnitTrace& trace) {
    queue_.push_back({in, golden, trace});
}

Unit Scoreboard::locate(const Pending& e, const PixelFx& got, const ProbeFx* probe,
                         std::string* detail) const {
    std::ostringstream os;
    const UnitTrace& t = e.trace;
    if (probe) {
        // Units 1-3 from the probes, octave by octave.
        for (int i = 0; i < t.octaves && i < int(probe->n.size()); ++i) {
            for (int k = 0; k < 3; ++k)
                if (probe->lat[i][k] != t.lat[i][k] || probe->frac[i][k] != t.frac[i][k]) {
                    os << "octave " << i << " axis " << k << ": lattice/frac rtl " << probe->lat[i][k] << "/"
                       << probe->frac[i][k] << " golden " << t.lat[i][k] << "/" << t.frac[i][k];
                    *detail = os.str();
                    return Unit::Transform;
                }
        }
        for (int i = 0; i < t.octaves && i < int(probe->n.size()); ++i) {
            bool g = false;
            for (int k = 0; k < 3; ++k) g = g || probe->g[i][k] != t.g[i][k];
            if (probe->n[i] != t.n[i] || g) {
                os << "octave " << i << ": n rtl " << probe->n[i] << " golden " << t.n[i] << ", grad rtl ("
                   << probe->g[i][0] << ", " << probe->g[i][1] << ", " << probe->g[i][2] << ") golden (" << t.g[i][0]
                   << ", " << t.g[i][1] << ", " << t.g[i][2] << ")";
                *detail = os.str();
                return Unit::Noise;
            }
        }
        if (probe->q != t.q) {
            os << "q rtl " << probe->q << " golden " << t.q;
            *detail = os.str();
            return Unit::Quadric;
        }
    }
    const PixelFx& x = e.golden;
    if (got.f != x.f || got.grad[0] != x.grad[0] || got.grad[1] != x.grad[1] || got.grad[2] != x.grad[2]) {
        os << "f rtl " << got.f << " golden " << x.f << ", grad rtl (" << got.grad[0] << ", " << got.grad[1] << ", "
           << got.grad[2] << ") golden (" << x.grad[0] << ", " << x.grad[1] << ", " << x.grad[2] << ")";
        *detail = os.str();
        return Unit::Accumulate;
    }
    if (got.w != x.w) {
        os << "W rtl " << got.w << " golden " << x.w;
        *detail = os.str();
        return Unit::FilterWidth;
    }
    if (got.rgba != x.rgba) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "RGBA rtl 0x%08x golden 0x%08x", got.rgba, x.rgba);
        *detail = buf;
        return Unit::ClutFilter;
    }
    return Unit::Count;  // every unit's value and output agrees
}

void Scoreboard::observe(const PixelFx& got, const ProbeFx* probe) {
    if (queue_.empty() || queue_.front().in.tag != got.tag) {
        // Not the next pixel in order: duplicated, reordered, or never sent.
        ++unexpected_;
        if (reports_.size() < maxReports_) {
            Mismatch m;
            m.got = got;
            m.detail = "pixel tag " + std::to_string(got.tag) + " out of order (expected " +
                       (queue_.empty() ? std::string("none") : std::to_string(queue_.front().in.tag)) + ")";
            reports_.push_back(m);
        }
        return;
    }
    Pending e = std::move(queue_.front());
    queue_.pop_front();
    ++checked_;
    // Every probed unit value and every output field must agree, bit for bit.
    Mismatch m;
    m.unit = locate(e, got, probe, &m.detail);
    if (m.unit == Unit::Count) return;
    ++mismatches_;
    m.input = e.in;
    m.expected = e.golden;
    m.got = got;
    ++byUnit_[m.unit];
    if (reports_.size() < maxReports_) {
        m.detail += "\n" + e.trace.describe(p_);
        reports_.push_back(m);
    }
}

void Scoreboard::finish() {
    lost_ += queue_.size();
    queue_.clear();
}

std::string Scoreboard::summary() const {
    std::ostringstream os;
    os << (passed() ? "PASSED" : "FAILED") << ": " << checked_ << " pixels checked, " << mismatches_
       << " mismatches, " << lost_ << " lost, " << unexpected_ << " out of order or unknown\n";
    for (const auto& [unit, n] : byUnit_) os << "  first differing unit " << toString(unit) << ": " << n << "\n";
    for (const auto& m : reports_) {
        os << "  pixel " << m.input.tag << " s (" << m.input.s[0] << ", " << m.input.s[1] << ", " << m.input.s[2]
           << ") J (" << m.input.j[0] << ", " << m.input.j[1] << ", " << m.input.j[2] << ", " << m.input.j[3] << ", "
           << m.input.j[4] << ", " << m.input.j[5] << "): unit " << toString(m.unit) << ": " << m.detail << "\n";
    }
    return os.str();
}

}  // namespace pst
