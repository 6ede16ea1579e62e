// voxlab: FLIP error maps as images, in the magma colour map.
#include <algorithm>
#include <cmath>

#include "voxlab/flip.h"

namespace voxlab {

namespace {

// 33 colours of matplotlib's "magma" (S. van der Walt and N. Smith,
// matplotlib colormaps, CC0), its 256-entry table at entries
// round(k * 255 / 32), k = 0..32, shown as comments. Interpolating them
// linearly reproduces the full table to within 0.0046 (1.2 / 255).
constexpr float kMagma[33][3] = {
    {0.001462f, 0.000466f, 0.013866f},  // 0
    {0.013708f, 0.011771f, 0.068667f},  // 8
    {0.039608f, 0.031090f, 0.133515f},  // 16
    {0.074257f, 0.052017f, 0.202660f},  // 24
    {0.113094f, 0.065492f, 0.276784f},  // 32
    {0.159018f, 0.068354f, 0.352688f},  // 40
    {0.211718f, 0.061992f, 0.418647f},  // 48
    {0.265447f, 0.060237f, 0.461840f},  // 56
    {0.316654f, 0.071690f, 0.485380f},  // 64
    {0.366012f, 0.090314f, 0.497960f},  // 72
    {0.414709f, 0.110431f, 0.504662f},  // 80
    {0.463508f, 0.129893f, 0.507652f},  // 88
    {0.512831f, 0.148179f, 0.507648f},  // 96
    {0.562866f, 0.165368f, 0.504692f},  // 104
    {0.613617f, 0.181811f, 0.498536f},  // 112
    {0.664915f, 0.198075f, 0.488836f},  // 120
    {0.716387f, 0.214982f, 0.475290f},  // 128
    {0.761077f, 0.231214f, 0.460162f},  // 135
    {0.810855f, 0.252861f, 0.439305f},  // 143
    {0.857763f, 0.279857f, 0.415496f},  // 151
    {0.899552f, 0.314616f, 0.391037f},  // 159
    {0.933606f, 0.358764f, 0.370541f},  // 167
    {0.958464f, 0.411324f, 0.360014f},  // 175
    {0.975082f, 0.468861f, 0.363111f},  // 183
    {0.985693f, 0.528148f, 0.379371f},  // 191
    {0.992196f, 0.587502f, 0.406299f},  // 199
    {0.995810f, 0.646344f, 0.441361f},  // 207
    {0.997254f, 0.704611f, 0.482635f},  // 215
    {0.997019f, 0.762398f, 0.528821f},  // 223
    {0.995424f, 0.819875f, 0.579140f},  // 231
    {0.992831f, 0.877168f, 0.633109f},  // 239
    {0.989815f, 0.934329f, 0.690198f},  // 247
    {0.987053f, 0.991438f, 0.749504f},  // 255
};

}  // namespace

glm::vec3 magma(double t) {
    if (!(t >= 0.0)) t = 0.0;  // also catches NaN
    const double position = std::min(t, 1.0) * 32.0;
    const int k = std::min(int(position), 31);
    const float f = float(position - k);
    const glm::vec3 a(kMagma[k][0], kMagma[k][1], kMagma[k][2]);
    const glm::vec3 b(kMagma[k + 1][0], kMagma[k + 1][1], kMagma[k + 1][2]);
    return a + f * (b - a);
}

Image heatmap(const FlipResult& result) {
    Image image(result.width, result.height);
    for (int y = 0; y < result.height; ++y)
        for (int x = 0; x < result.width; ++x)
            image.set(x, y, glm::vec4(magma(result.map[std::size_t(y) * result.width + x]), 1.0f));
    return image;
}

}  // namespace voxlab
