// The unit tests' profile and seed: the profile the executable was built for
// (PST_PROFILE_PATH) and one seed per run, printed so that PST_SEED=<n> replays it.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "profile.h"

namespace pst::unit {

inline const Profile& prof() {
    static const Profile p = pst::loadProfile(PST_PROFILE_PATH);
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

}  // namespace pst::unit
