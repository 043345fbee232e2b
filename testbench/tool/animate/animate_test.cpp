// The flicker metric: temporal RMS error against the ground truth's own change.
#include "animate.h"

#include <cmath>

#include <gtest/gtest.h>

namespace pst {
namespace {

Image flat(float v) {
    Image im(2, 2, 4);
    for (size_t i = 0; i < im.data.size(); ++i) im.data[i] = (i % 4 == 3) ? 1.f : v;
    return im;
}

TEST(Flicker, FollowingTheTruthExactlyIsZero) {
    EXPECT_EQ(temporalRms(flat(0.2f), flat(0.5f), flat(0.2f), flat(0.5f)), 0.0);
    // An offset that stays put is an error, not flicker.
    EXPECT_NEAR(temporalRms(flat(0.3f), flat(0.6f), flat(0.2f), flat(0.5f)), 0.0, 1e-7);
}

TEST(Flicker, AStillImageUnderAChangingTruthFlickersByTheTruthsChange) {
    EXPECT_NEAR(temporalRms(flat(0.4f), flat(0.4f), flat(0.2f), flat(0.5f)), 0.3, 1e-7);
}

TEST(Flicker, OnlyRgbCountsAndOnePixelOfFour) {
    Image a = flat(0.f), b = flat(0.f), t = flat(0.f);
    b.pixel(1, 1)[0] = 0.6f;   // one channel of one pixel: sqrt(0.36 / 12)
    b.pixel(0, 0)[3] = 0.0f;   // alpha is ignored
    EXPECT_NEAR(temporalRms(a, b, t, t), std::sqrt(0.36 / 12.0), 1e-7);
}

}  // namespace
}  // namespace pst
