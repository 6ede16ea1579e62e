// Test support: the README's axis-view table, restated for the tests
// independently of camera.cpp. Each view names the world axis (0 x, 1 y,
// 2 z) and sign of the ray direction, image right and image down.
#pragma once

namespace voxlab::testing {

struct AxisView {
    const char* name;
    int fwdAxis, fwdSign, rightAxis, rightSign, downAxis, downSign;
};

inline constexpr AxisView kAxisViews[] = {
    {"+z", 2, +1, 0, +1, 1, +1}, {"-z", 2, -1, 0, -1, 1, +1}, {"+x", 0, +1, 2, -1, 1, +1},
    {"-x", 0, -1, 2, +1, 1, +1}, {"+y", 1, +1, 0, -1, 2, +1}, {"-y", 1, -1, 0, +1, 2, +1},
};

}  // namespace voxlab::testing
