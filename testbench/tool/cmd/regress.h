// pst regress, shared by its two modes (regress.cpp registers them): every scene x profile
// through the RTL against the golden model (regress_scenes.cpp), or constrained-random
// fragments (regress_random.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common.h"
#include "random_regress.h"

namespace pst::cli {

struct RegressArgs {
    std::vector<std::string> scenes;
    int size = 64;
    std::string out, images, junit, html;
    bool quiet = false, list = false;
    uint64_t injectAssert = UINT64_MAX;
    std::string injectFault;            // self-test: a golden unit perturbed (a mismatch on purpose)
    std::vector<uint64_t> seeds;        // the runs' seeds (--reseed: random ones, else one)
    std::string waves;                  // folder of the FST windows of failing runs ("" = none)
    std::string wavesShown;             // that folder as the messages name it (waves: the output
                                        // transaction's temporary folder until the commit)
    uint64_t wavesBefore = 2000, wavesAfter = 50;   // the window around the first mismatch
};

// The unit named by --inject-fault (InputError if none is).
Unit unitByName(const std::string& name);

int runRegressScenes(const RegressArgs& a, const HwArgs& hw);
int runRegressRandom(const RegressArgs& a, const HwArgs& hw, RandomRegressOptions o);

}  // namespace pst::cli
