// pst regress --random N: constrained-random textures and fragments (testbench/verify/random),
// per profile and per seed (--reseed).
#include <cstdio>
#include <iostream>

#include <unistd.h>

#include "imageio.h"
#include "junit.h"
#include "provenance.h"
#include "regress.h"

namespace pst::cli {

int runRegressRandom(const RegressArgs& a, const HwArgs& hw, RandomRegressOptions o) {
    int failures = 0;
    std::vector<JunitCase> cases;
    nlohmann::json all = nlohmann::json::array();
    std::printf("%-14s %10s %9s %9s %10s %10s %12s\n", "profile", "fragments", "textures", "mismatch", "cyc/pixel",
                "seconds", "fragments/s");
    std::vector<Profile> profiles;
    for (const std::string& name : hw.profiles) profiles.push_back(profileByName(name, true, false));
    const bool reseeded = a.seeds.size() > 1;
    for (uint64_t seed : a.seeds) {
        o.seed = seed;
        if (reseeded) {
            std::printf("seed %llu\n", (unsigned long long)seed);
            std::fflush(stdout);
        }
        for (const Profile& p : profiles) {
            const std::string& name = p.name;
            if (!a.quiet && isatty(STDERR_FILENO))
                o.progress = [&](uint64_t done, uint64_t total) {
                    std::fprintf(stderr, "\r%s: %llu / %llu", p.name.c_str(), (unsigned long long)done,
                                 (unsigned long long)total);
                    if (done >= total) std::fprintf(stderr, "\n");
                };
            const RandomRegressResult r = runRandomRegress(p, p.name, o);
            std::printf("%-14s %10llu %9llu %9llu %10.3f %10.1f %12.0f\n", p.name.c_str(),
                        (unsigned long long)r.fragments, (unsigned long long)r.textures, (unsigned long long)r.mismatches,
                        r.fragments ? double(r.cycles) / double(r.fragments) : 0.0, r.seconds,
                        r.seconds > 0 ? double(r.fragments) / r.seconds : 0.0);
            std::fflush(stdout);
            JunitCase jc{"regress.random." + p.name, "seed " + std::to_string(o.seed) + " fragments " +
                         std::to_string(r.firstFragment) + ".." + std::to_string(r.firstFragment + r.fragments),
                         r.seconds, !r.passed, "", ""};
            // The command that replays the first failure alone (the segment holding it, same inputs).
            std::string replay;
            if (r.firstBad != UINT64_MAX) {
                replay = "pst regress --random " + std::to_string(r.replayFragments) + " --seed " + std::to_string(o.seed) +
                         " --from " + std::to_string(r.firstBad) + " --batch " + std::to_string(o.maxBatch) +
                         " --profile " + name + " --probes";
                if (o.injectAssert != UINT64_MAX) replay += " --inject-assert " + std::to_string(o.injectAssert);
                if (!a.injectFault.empty()) replay += " --inject-fault " + a.injectFault;
            }
            all.push_back({{"profile", p.name},
                           {"seed", o.seed},
                           {"first_fragment", r.firstFragment},
                           {"fragments", r.fragments},
                           {"textures", r.textures},
                           {"mismatches", r.mismatches},
                           {"first_bad", r.firstBad == UINT64_MAX ? nlohmann::json(nullptr) : nlohmann::json(r.firstBad)},
                           {"assertion", r.assertion ? nlohmann::json({{"cycle", r.assertionCycle}}) : nlohmann::json(nullptr)},
                           {"assertions_verilated", asserted(name)},
                           {"replay", replay.empty() ? nlohmann::json(nullptr) : nlohmann::json(replay)},
                           {"cycles_per_pixel", r.fragments ? double(r.cycles) / double(r.fragments) : 0.0},
                           {"cycles", r.cycles},
                           {"seconds", r.seconds},
                           {"rtl_seconds", r.rtlSeconds},
                           {"golden_seconds", r.goldenSeconds},
                           {"passed", r.passed}});
            if (!r.passed) {
                ++failures;
                const std::string what = r.assertion ? "RTL assertion" : "mismatch";
                const std::string at = r.firstBad == UINT64_MAX ? std::string("?") : std::to_string(r.firstBad);
                jc.message = r.assertion ? "RTL assertion at cycle " + std::to_string(r.assertionCycle) + ", fragment " + at
                                         : std::to_string(r.mismatches) + " mismatches, first at fragment " + at;
                jc.output = r.report + (replay.empty() ? "" : "replay alone: " + replay + "\n");
                cases.push_back(jc);
                std::cout << r.report;
                if (!replay.empty())
                    std::cout << "first " << what << ": seed " << o.seed << ", fragment " << r.firstBad
                              << "; replay alone: " << replay << "\n";
                if (!asserted(name))
                    std::cout << "(" << name << " is verilated here without assertions; a build configured with "
                              << "-DPST_SIM_ASSERT=ON replays it with them)\n";
            } else {
                cases.push_back(jc);
            }
        }
    }
    if (!a.out.empty()) {
        nlohmann::json doc = provenance();
        doc["runs"] = all;
        writeTextFile(a.out, doc.dump(2) + "\n");
    }
    if (!a.junit.empty()) writeJunit(a.junit, "pst regress --random", cases, junitProperties());
    std::string seeds;
    for (uint64_t s : a.seeds) seeds += (seeds.empty() ? "" : ", ") + std::to_string(s);
    std::printf("%s: %zu profiles, %d failed (%s %s)\n", failures ? "FAILED" : "PASSED", hw.profiles.size() * a.seeds.size(),
                failures, reseeded ? "seeds" : "seed", seeds.c_str());
    return failures ? 1 : 0;
}

}  // namespace pst::cli
