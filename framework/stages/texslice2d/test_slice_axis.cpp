// The slice axis of 2D texture slicing (slice_axis.h), checked on the CPU (no
// GL) against the contract's own words: axis-aligned directions, both sides
// of the 45-degree switch between two axes, and exact ties.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "voxlab/slice_axis.h"

namespace voxlab::testing {
namespace {

using glm::dvec3;

constexpr double kPi = 3.14159265358979323846;

std::string str(dvec3 p) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
    return s.str();
}

TEST(SliceAxis, AxisAlignedDirections) {
    for (int axis = 0; axis < 3; ++axis)
        for (double s : {1.0, -1.0, 0.01, -250.0}) {
            dvec3 d(0.0);
            d[axis] = s;
            EXPECT_EQ(chooseSliceAxis(d), axis) << str(d);
        }
}

TEST(SliceAxis, SwitchesAt45Degrees) {
    // Turning from axis i towards axis j (either way round, either overall
    // sign, with or without a small third component): axis i up to 45
    // degrees, axis j beyond.
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            if (i == j) continue;
            const int k = 3 - i - j;
            for (double degrees : {44.0, 46.0, 10.0, 80.0, 44.999, 45.001})
                for (double sj : {1.0, -1.0})
                    for (double overall : {1.0, -1.0})
                        for (double third : {0.0, 0.1, -0.3}) {
                            const double t = degrees * kPi / 180.0;
                            dvec3 d(0.0);
                            d[i] = std::cos(t);
                            d[j] = sj * std::sin(t);
                            d[k] = third;
                            d *= overall;
                            EXPECT_EQ(chooseSliceAxis(d), degrees < 45.0 ? i : j) << degrees << " deg " << str(d);
                        }
        }
}

TEST(SliceAxis, TiesGoToTheLowerAxis) {
    // Components equal in absolute value (exactly, whatever the signs).
    struct Case {
        dvec3 d;
        int axis;
    };
    for (const Case& c : std::vector<Case>{{{1, 1, 0}, 0},
                                           {{-1, 1, 0}, 0},
                                           {{1, -1, 0.5}, 0},
                                           {{1, 0, 1}, 0},
                                           {{-2, 0.3, -2}, 0},
                                           {{0, 1, 1}, 1},
                                           {{0.2, -3, 3}, 1},
                                           {{0, -1, -1}, 1},
                                           {{1, 1, 1}, 0},
                                           {{-1, -1, -1}, 0},
                                           {{0.5, -0.5, 0.5}, 0},
                                           {{-1, 1, 1}, 0}})
        EXPECT_EQ(chooseSliceAxis(c.d), c.axis) << str(c.d);
    // Just off the tie the larger component wins.
    EXPECT_EQ(chooseSliceAxis({1, std::nextafter(1.0, 2.0), 0}), 1);
    EXPECT_EQ(chooseSliceAxis({0, 1, std::nextafter(1.0, 2.0)}), 2);
    EXPECT_EQ(chooseSliceAxis({std::nextafter(1.0, 2.0), 1, 1}), 0);
}

}  // namespace
}  // namespace voxlab::testing
