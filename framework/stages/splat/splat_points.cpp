// voxlab: splatting's points (see splatting.h).
#include "voxlab/splatting.h"

#include "voxlab/error.h"

namespace voxlab {

std::vector<glm::vec4> splatPoints(const Volume& volume, const TransferFunction& tf, const SplatOrder& order) {
    volume.requireInMemory("splatting");
    const glm::ivec3 d = volume.dims();
    for (int a = 0; a < 3; ++a) {
        const int axis = order.axes[std::size_t(a)], step = order.step[std::size_t(a)];
        if (axis < 0 || axis > 2 || (step != 1 && step != -1))
            throw Error("splatOrder gave axes " + std::to_string(order.axes[0]) + " " + std::to_string(order.axes[1]) +
                        " " + std::to_string(order.axes[2]) + " and steps that are not +1 or -1");
    }
    if (order.axes[0] == order.axes[1] || order.axes[1] == order.axes[2] || order.axes[0] == order.axes[2])
        throw Error("splatOrder gave an axis twice: each of 0, 1, 2 must be one loop");
    // Which values the transfer function shows: for 8- and 16-bit data a
    // table over the value range, read once per distinct value.
    std::vector<char> table;
    const double lo = volume.minValue();
    if (volume.type() != VoxelType::Float32)
        for (double v = lo; v <= volume.maxValue(); v += 1.0) table.push_back(tf.evaluate(v).a > 0.0f);
    const auto shown = [&](double v) {
        return table.empty() ? tf.evaluate(v).a > 0.0f : table[std::size_t(v - lo)] != 0;
    };
    std::vector<glm::vec4> points;
    const glm::dvec3 spacing = volume.spacing();
    glm::ivec3 ijk;
    const auto range = [&](int loop) {
        const int axis = order.axes[std::size_t(loop)], n = d[axis];
        const bool down = order.step[std::size_t(axis)] < 0;
        return std::array<int, 3>{down ? n - 1 : 0, down ? -1 : n, down ? -1 : 1};  // first, end, step
    };
    const auto outer = range(0), middle = range(1), inner = range(2);
    for (int a = outer[0]; a != outer[1]; a += outer[2])
        for (int b = middle[0]; b != middle[1]; b += middle[2])
            for (int c = inner[0]; c != inner[1]; c += inner[2]) {
                ijk[order.axes[0]] = a, ijk[order.axes[1]] = b, ijk[order.axes[2]] = c;
                const double v = volume.value(ijk.x, ijk.y, ijk.z);
                if (!shown(v)) continue;
                const glm::dvec3 centre = (glm::dvec3(ijk) + 0.5) * spacing;
                points.emplace_back(float(centre.x), float(centre.y), float(centre.z), float(v));
            }
    return points;
}

}  // namespace voxlab
