// The unit tests' profile, seed and random count: the profile the executable was built for
// (PST_PROFILE_PATH, relative to the source tree: sourceDir()), one seed per run, printed so that PST_SEED=<n> replays it, and how many
// random vectors a test draws (a tenth of its long count by default, the whole of it with
// PST_UNIT_LONG=1: ctest -L long).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "profile.h"
#include "source_dir.h"

namespace pst::unit {

inline const Profile& prof() {
    static const Profile p = pst::loadProfile(pst::sourceDir() + "/" PST_PROFILE_PATH);
    return p;
}

// The run's seed: PST_SEED when set, else a random one; `test` names the test in the line
// that prints it.
inline uint64_t seed(const char* test) {
    static const uint64_t s = [test] {
        const char* e = std::getenv("PST_SEED");
        const uint64_t v = e ? std::strtoull(e, nullptr, 0) : std::random_device{}() * 0x100000001ull;
        std::printf("%s[%s]: seed %llu (replay with PST_SEED=%llu)\n", test, prof().name.c_str(),
                    (unsigned long long)v, (unsigned long long)v);
        return v;
    }();
    return s;
}

// The number of random vectors of a test whose long run draws LONG_COUNT: all of them with
// PST_UNIT_LONG=1 in the environment (the `long` ctest label), a tenth by default. The special
// values and boundaries of each test run in both.
inline int randomCount(int longCount) {
    static const bool full = [] {
        const char* e = std::getenv("PST_UNIT_LONG");
        return e && *e && std::string(e) != "0";
    }();
    return full ? longCount : longCount / 10;
}

}  // namespace pst::unit
