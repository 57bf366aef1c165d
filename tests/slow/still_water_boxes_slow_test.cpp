// Still water at mu = 1e-3 for 2 s in three boxes whose sides are not multiples of h, at two
// spacings each (see tests/integration/still_water_boxes_test.cpp for what and why).
#include "tests/integration/still_water_boxes.h"

namespace pfem {
namespace {

class StillWaterBoxesSlow : public ::testing::TestWithParam<StillBox> {};

TEST_P(StillWaterBoxesSlow, StaysAtRestForTwoSeconds) { expect_still(GetParam()); }

INSTANTIATE_TEST_SUITE_P(ThreeBoxesTwoSpacings, StillWaterBoxesSlow,
                         ::testing::Values(StillBox{0.2, 0.15, 0.1, 0.004, 2.0}, StillBox{0.2, 0.15, 0.1, 0.0065, 2.0},
                                           StillBox{0.23, 0.17, 0.11, 0.004, 2.0}, StillBox{0.23, 0.17, 0.11, 0.0065, 2.0},
                                           StillBox{0.37, 0.13, 0.083, 0.004, 2.0}, StillBox{0.37, 0.13, 0.083, 0.0065, 2.0}));

}  // namespace
}  // namespace pfem
