// voxlab: cubic B-spline coefficients (see bspline.h).
#include "voxlab/bspline.h"

#include <algorithm>

namespace voxlab {

// The Thomas algorithm on the system of bspline.h: sub- and super-diagonal
// 1/6, diagonal 4/6 (5/6 in the first and last rows, where the clamped
// neighbour is the coefficient itself). A line of one value is its own
// coefficient.
void bsplineCoefficientsLine(std::vector<double>& s) {
    const std::size_t n = s.size();
    if (n < 2) return;
    std::vector<double> upper(n);  // the eliminated super-diagonal
    const double off = 1.0 / 6.0;
    double diagonal = 5.0 / 6.0;
    upper[0] = off / diagonal;
    s[0] /= diagonal;
    for (std::size_t k = 1; k < n; ++k) {
        diagonal = (k + 1 == n ? 5.0 / 6.0 : 4.0 / 6.0) - off * upper[k - 1];
        upper[k] = off / diagonal;
        s[k] = (s[k] - off * s[k - 1]) / diagonal;
    }
    for (std::size_t k = n - 1; k-- > 0;) s[k] -= upper[k] * s[k + 1];
}

std::vector<float> bsplineCoefficients(const Volume& volume) {
    volume.requireInMemory("the cubic B-spline's coefficients");
    const glm::ivec3 d = volume.dims();
    std::vector<double> c(volume.voxelCount());
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = volume.valueAt(i);
    const std::size_t stride[3] = {1, std::size_t(d.x), std::size_t(d.x) * std::size_t(d.y)};
    std::vector<double> line;
    for (int axis = 0; axis < 3; ++axis) {
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        line.resize(std::size_t(d[axis]));
        for (int j = 0; j < d[b]; ++j)
            for (int i = 0; i < d[a]; ++i) {
                const std::size_t start = std::size_t(i) * stride[a] + std::size_t(j) * stride[b];
                for (int k = 0; k < d[axis]; ++k) line[std::size_t(k)] = c[start + std::size_t(k) * stride[axis]];
                bsplineCoefficientsLine(line);
                for (int k = 0; k < d[axis]; ++k) c[start + std::size_t(k) * stride[axis]] = line[std::size_t(k)];
            }
    }
    return std::vector<float>(c.begin(), c.end());
}

}  // namespace voxlab
