#include "random_regress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "driver.h"
#include "fixed.h"
#include "interrupt.h"
#include "rtl_model.h"
#include "scoreboard.h"

namespace pst {
namespace {

uint64_t mix(uint64_t a, uint64_t b) {
    // splitmix64 finalizer of a combined word: independent streams per (seed, index).
    uint64_t z = a * 0x9e3779b97f4a7c15ull + b + 0x632be59bd9b4e019ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// A segment's seeds: batch sizes, content (textures, fragments, rates), RTL gaps and stalls.
uint64_t segmentSeed(uint64_t seed, uint64_t g) { return mix(seed, g); }

std::vector<int> batchSizes(const RandomRegressOptions& o, uint64_t g) {
    RandomStream r(mix(segmentSeed(o.seed, g), 1));
    std::vector<int> sizes(size_t(std::max(1, o.batchesPerSegment)));
    for (int& n : sizes) n = int(r.range(1, std::max(1, o.maxBatch)));
    return sizes;
}

glm::dvec4 randomColour(RandomStream& r) { return {r.uniform(), r.uniform(), r.uniform(), r.uniform()}; }

// The colour table: uniform noise, a ramp between two colours, a constant (black, white or
// any), or stripes of a random period (sharp edges for the filters).
std::vector<glm::dvec4> randomTable(RandomStream& r, int n) {
    std::vector<glm::dvec4> e(static_cast<size_t>(n));
    switch (r.range(0, 3)) {
        case 0:
            for (auto& c : e) c = randomColour(r);
            break;
        case 1: {
            const glm::dvec4 a = randomColour(r), b = randomColour(r);
            for (int i = 0; i < n; ++i) e[size_t(i)] = a + (b - a) * (double(i) / std::max(1, n - 1));
            break;
        }
        case 2: {
            const int k = int(r.range(0, 2));
            const glm::dvec4 c = k == 0 ? glm::dvec4(0.0) : k == 1 ? glm::dvec4(1.0) : randomColour(r);
            std::fill(e.begin(), e.end(), c);
            break;
        }
        default: {
            const glm::dvec4 a = randomColour(r), b = randomColour(r);
            const int period = int(r.range(1, n));
            for (int i = 0; i < n; ++i) e[size_t(i)] = (i / period) % 2 ? b : a;
            break;
        }
    }
    return e;
}

// A per-texture (or per-batch) magnitude cap: log2 of the largest typical value.
int randomCap(RandomStream& r, const FixedFormat& f) { return int(r.range(-f.fracBits, f.intBits - 1)); }

}  // namespace

uint64_t RandomStream::next() {
    uint64_t z = (s_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double RandomStream::uniform() { return double(next() >> 11) * 0x1.0p-53; }

int64_t RandomStream::range(int64_t lo, int64_t hi) {
    const uint64_t span = uint64_t(hi - lo) + 1;
    return span == 0 ? int64_t(next()) : lo + int64_t(next() % span);
}

double randomFormatValue(RandomStream& r, const FixedFormat& f, int maxExp) {
    const int w = f.width();
    const double u = r.uniform();
    const double sign = r.chance(0.5) ? -1.0 : 1.0;
    if (u < 0.08) return 0.0;
    if (u < 0.16) {  // the extremes and one LSB either side of zero
        const int64_t pick[4] = {fx::maxSigned(w), fx::minSigned(w), 1, -1};
        return std::ldexp(double(pick[r.range(0, 3)]), -f.fracBits);
    }
    if (u < 0.24) return std::ldexp(double(r.range(fx::minSigned(w), fx::maxSigned(w))), -f.fracBits);
    if (u < 0.28) return sign * std::ldexp(double(fx::maxSigned(w)), -f.fracBits) * r.uniform(1.0, 4.0);
    // Log-uniform magnitude from below one LSB to 2^(maxExp + 1).
    return sign * std::exp2(r.uniform(double(-f.fracBits - 1), double(maxExp + 1)));
}

Texture randomTexture(RandomStream& r, const Profile& p) {
    Texture t;
    t.name = "random";
    const int qe = randomCap(r, p.quadric);
    double* coef[10] = {&t.quadric.A, &t.quadric.B, &t.quadric.C, &t.quadric.D, &t.quadric.E,
                        &t.quadric.F, &t.quadric.G, &t.quadric.H, &t.quadric.I, &t.quadric.J};
    for (double* c : coef) *c = r.chance(0.3) ? 0.0 : randomFormatValue(r, p.quadric, qe);

    // 0..Octaves octaves; sometimes one more than the profile holds (the driver drops it).
    const int n = r.chance(0.1) ? p.octaves + 1 : int(r.range(0, p.octaves));
    // Lattice textures: integer diagonal M and integer o, so integer s lands on lattice planes.
    const bool lattice = r.chance(0.2);
    const int me = randomCap(r, p.matrix), oe = randomCap(r, p.offset), ae = randomCap(r, p.amplitude);
    for (int i = 0; i < n; ++i) {
        Octave o;
        if (lattice) {
            o.M = glm::dmat3(0.0);
            for (int k = 0; k < 3; ++k) o.M[k][k] = double(r.range(-4, 4));
            for (int k = 0; k < 3; ++k) o.offset[k] = double(r.range(-64, 64));
        } else {
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 3; ++k) o.M[c][k] = randomFormatValue(r, p.matrix, me);
            for (int k = 0; k < 3; ++k) o.offset[k] = randomFormatValue(r, p.offset, oe);
        }
        o.amplitude = randomFormatValue(r, p.amplitude, ae);
        t.octaves.push_back(o);
    }
    t.noise = p.noise;
    if (p.noise.basis == NoiseBasis::Worley) {
        // The worley unit's coefficients: random over the register range (-8, 8), some 0 or
        // at the ends; 0 beyond the unit's order (the driver refuses others).
        const double cmax = 8.0 - 1.0 / 4096.0;
        for (int k = 0; k < 4; ++k) {
            double c = r.chance(0.2) ? 0.0 : r.chance(0.1) ? (r.chance(0.5) ? cmax : -cmax) : (2 * r.uniform() - 1) * cmax;
            t.noise.coef[size_t(k)] = k < p.noiseWorleyOrder ? c : 0.0;
        }
    }
    t.norm = p.filterNorm;
    const WrapMode wrap = r.chance(0.5) ? WrapMode::Clamp : WrapMode::Mod;
    t.clut = ColorMap(randomTable(r, p.clutSize()), wrap);
    static const FilterKind kinds[5] = {FilterKind::None, FilterKind::MipNearest, FilterKind::MipLinear,
                                        FilterKind::Sat, FilterKind::Box};
    t.filter = kinds[r.range(0, 4)];
    // Bandlimited octaves on a profile with the fade unit (other profiles draw nothing more).
    if (p.bandlimit()) t.bandlimit = r.chance(0.7) ? Bandlimit::Isotropic : Bandlimit::Off;
    // The width cap on a profile with its unit (other profiles draw nothing more); with a random
    // quadric it is mostly none (the quadric varies): the regression also writes arbitrary caps.
    if (p.widthCap()) t.widthCap = r.chance(0.7);
    // A subband unit with its anisotropic filter: its weights instead, of a random sigma.
    if (p.noise.basis == NoiseBasis::Subband && p.noiseSubbandOrientations != 0) {
        if (t.bandlimit == Bandlimit::Isotropic) t.bandlimit = Bandlimit::Anisotropic;
        t.noise.sigma = std::exp2(r.uniform(-3.0, 2.0));
    }
    return t;
}

std::vector<FragmentFx> randomFragments(RandomStream& r, const Profile& p, uint32_t firstTag, size_t n) {
    const int se = randomCap(r, p.coord), je = randomCap(r, p.jacobian);
    const double latticeRate = r.chance(0.3) ? r.uniform() : 0.0;
    // Coherent streams (a scanline: small steps from a start point) or independent points.
    const bool walk = r.chance(0.3);
    glm::dvec3 s0(randomFormatValue(r, p.coord, se), randomFormatValue(r, p.coord, se),
                  randomFormatValue(r, p.coord, se));
    const double step = std::exp2(r.uniform(double(-p.coord.fracBits), 2.0));
    std::vector<FragmentFx> out;
    out.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        glm::dvec3 s, dx, dy;
        for (int k = 0; k < 3; ++k) {
            if (walk) {
                s0[k] += step * r.uniform(-1.0, 1.0);
                s[k] = s0[k];
            } else {
                s[k] = randomFormatValue(r, p.coord, se);
            }
            if (latticeRate > 0 && r.chance(latticeRate)) s[k] = std::round(s[k]);
            dx[k] = randomFormatValue(r, p.jacobian, je);
            dy[k] = randomFormatValue(r, p.jacobian, je);
        }
        if (r.chance(0.05)) dx = dy = glm::dvec3(0.0);  // a zero Jacobian
        out.push_back(quantizeFragment(p, firstTag + uint32_t(i), s, dx, dy));
    }
    return out;
}

uint64_t segmentStart(const RandomRegressOptions& o, uint64_t index, uint64_t* segment) {
    uint64_t start = 0;
    for (uint64_t g = 0;; ++g) {
        uint64_t len = 0;
        for (int n : batchSizes(o, g)) len += uint64_t(n);
        if (index < start + len) {
            if (segment) *segment = g;
            return start;
        }
        start += len;
    }
}

std::vector<uint64_t> segmentStarts(const RandomRegressOptions& o) {
    std::vector<uint64_t> out;
    const uint64_t end = o.from + o.fragments;
    uint64_t start = 0;
    for (uint64_t g = 0; start < end; ++g) {
        uint64_t len = 0;
        for (int n : batchSizes(o, g)) len += uint64_t(n);
        if (start + len > o.from) out.push_back(start);
        start += len;
    }
    return out;
}

RandomRegressResult runRandomRegress(const Profile& p, const std::string& rtlName, const RandomRegressOptions& o) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    RandomRegressResult res;
    uint64_t g = 0;
    uint64_t idx = segmentStart(o, o.from, &g);
    res.firstFragment = idx;
    const uint64_t end = o.from + o.fragments;
    for (; idx < end; ++g) {
        const uint64_t segSeed = segmentSeed(o.seed, g);
        const std::vector<int> sizes = batchSizes(o, g);
        RandomStream r(mix(segSeed, 2));
        SimOptions so;
        so.seed = mix(segSeed, 3);
        so.inputGapRate = r.chance(0.25) ? 0.0 : r.uniform(0.0, o.maxGapRate);
        so.outputStallRate = r.chance(0.25) ? 0.0 : r.uniform(0.0, o.maxStallRate);
        // One segment in five stalls in bursts (rare stalls of 16..256 cycles) instead, long
        // enough to fill the output skid buffers and hold the serial stages at their last step
        // (coverage: back-pressure while full). Its own stream, so the other draws stay as they were.
        RandomStream rb(mix(segSeed, 4));
        if (o.maxStallRate > 0.0 && rb.chance(0.2)) {
            so.outputStallRate = rb.uniform(0.002, 0.02);
            so.outputStallBurst = int(rb.range(16, 256));
        }
        uint64_t segEnd = idx;
        for (int n : sizes) segEnd += uint64_t(n);
        segEnd = std::min(segEnd, end);
        if (o.injectAssert >= idx && o.injectAssert < segEnd) so.busyWriteAfter = o.injectAssert - idx + 1;
        auto segmentName = [&] {
            std::ostringstream os;
            os << "segment " << g << " (gap rate " << so.inputGapRate << ", stall rate " << so.outputStallRate
               << (so.outputStallBurst > 1 ? " in bursts of 1.." + std::to_string(so.outputStallBurst) : std::string())
               << "): ";
            return os.str();
        };
        auto rtl = makeRtlModel(rtlName, so);
        GoldenPipeline golden(p);
        Scoreboard board(p, o.maxReports);
        Texture tex;
        TextureProgram prog;
        bool programmed = false;
        std::string assertion;         // what the RtlAssertionError said, if one fired
        for (size_t b = 0; b < sizes.size() && idx < end; ++b) {
            // A new texture, or (as for an unfiltered image) only a new control word.
            RegWrites writes;
            if (!programmed || !r.chance(0.2)) {
                tex = randomTexture(r, p);
                prog = programTexture(p, tex);
                writes = prog.writes;
                programmed = true;
                // Fade unit: sometimes arbitrary table entries (all FadeBits, above 1.0 too: alpha clamps).
                if (p.bandlimit() && r.chance(0.3))
                    for (int k = 0; k < contract::kFadeEntries; ++k)
                        if (r.chance(0.5))
                            writes.push_back({uint16_t(contract::kRegFade + k),
                                              uint32_t(r.range(0, (1 << contract::kFadeBits) - 1))});
                // Fade unit: sometimes arbitrary term means (a basis of another mean; the whole F
                // range, its extremes too: the fade toward them saturates at the format's ends).
                if (p.bandlimit() && r.chance(0.3))
                    for (int i = 0; i < p.octaves; ++i) {
                        const int64_t lo = fx::minSigned(p.f.width()), hi = fx::maxSigned(p.f.width());
                        const int64_t v = r.chance(0.2) ? (r.chance(0.5) ? lo : hi) : int64_t(r.range(lo, hi));
                        writes.push_back({uint16_t(contract::kRegOctave + contract::kRegOctaveStride * i +
                                                   contract::kRegOctaveFm),
                                          uint32_t(uint64_t(v) & 0xffffffffu)});
                    }
                // Width cap: sometimes an arbitrary cap (0, small, any W, all ones).
                if (p.widthCap() && r.chance(0.5)) {
                    const int64_t wmax = fx::maxUnsigned(p.widthBits());
                    const double u = r.uniform();
                    const int64_t v = u < 0.1 ? 0 : u < 0.2 ? wmax : u < 0.6 ? int64_t(r.range(0, 1 << (p.widthFrac + 3)))
                                                                           : int64_t(r.range(0, wmax));
                    writes.push_back({contract::kRegWcap, uint32_t(v)});
                }
            } else {
                writes = {controlWrite(tex, int(r.range(0, 3)))};
            }
            ++res.textures;
            std::vector<FragmentFx> frags = randomFragments(r, p, uint32_t(idx), size_t(sizes[b]));
            if (frags.size() > end - idx) frags.resize(size_t(end - idx));

            const auto tg = Clock::now();
            for (const auto& [a, d] : writes) golden.write(a, d);
            for (const FragmentFx& f : frags) {
                if (o.fault != Unit::Count) golden.injectFault(f.tag >= o.faultFrom ? o.fault : Unit::Count);
                UnitTrace trace;
                const PixelFx px = golden.eval(f, &trace);
                board.expect(f, px, trace);
            }
            const auto tr = Clock::now();
            res.goldenSeconds += std::chrono::duration<double>(tr - tg).count();
            std::map<uint32_t, ProbeFx> probes;
            std::vector<PixelFx> got;
            // The verilated model's share of the time (the benchmark's RTL rate), however the run ends.
            struct RtlTimer {
                double& acc;
                Clock::time_point t;
                ~RtlTimer() { acc += std::chrono::duration<double>(Clock::now() - t).count(); }
            };
            try {
                RtlTimer timer{res.rtlSeconds, tr};
                rtl->write(writes);
                got = rtl->run(frags, prog.activeOctaves, o.probes ? &probes : nullptr);
            } catch (const RtlAssertionError& e) {
                // A failed run like a mismatch: named by the oldest fragment in flight, replayed
                // from there to the segment's end.
                res.assertion = true;
                res.assertionCycle = e.cycle;
                res.firstBad = idx + e.pixelsOut;
                res.fragments += e.pixelsOut;
                assertion = "RTL assertion at cycle " + std::to_string(e.cycle) + ", fragment " +
                            std::to_string(idx + e.pixelsOut) + " the oldest not yet out, " +
                            std::to_string(e.fragmentsIn) + " of the batch taken: " + e.what() + "\n";
                break;
            }
            for (const PixelFx& px : got) {
                auto it = probes.find(px.tag);
                board.observe(px, it == probes.end() ? nullptr : &it->second);
            }
            idx += frags.size();
            res.fragments += frags.size();
        }
        if (assertion.empty()) board.finish();
        res.cycles += rtl->busyCycles();
        ++res.segments;
        if (!assertion.empty()) {
            res.passed = false;
            res.mismatches += board.mismatches();
            for (const Mismatch& m : board.reports())   // pixels out before it that differed
                res.firstBad = std::min<uint64_t>(res.firstBad, m.unit == Unit::Count ? m.got.tag : m.input.tag);
            res.replayFragments = segEnd - res.firstBad;
            res.report += segmentName() + assertion;
            break;
        }
        if (!board.passed()) {
            res.passed = false;
            res.mismatches += board.mismatches() + board.lost() + board.unexpected();
            for (const Mismatch& m : board.reports())
                res.firstBad = std::min<uint64_t>(res.firstBad, m.unit == Unit::Count ? m.got.tag : m.input.tag);
            res.report += segmentName() + board.summary();
            break;  // the first failing segment is enough; replay it with --from
        }
        if (o.progress) o.progress(idx - res.firstFragment, end - res.firstFragment);
        throwIfInterrupted();   // SIGINT, SIGTERM: between segments
    }
    res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return res;
}

}  // namespace pst
