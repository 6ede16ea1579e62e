// voxlab info: what a volume file holds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "voxlab/error.h"
#include "voxlab/volume.h"

namespace voxlab::cli {
namespace {

// The value below which `fraction` of the voxels lie, from the histogram.
double percentile(const Histogram& h, double fraction) {
    const double target = fraction * double(h.total());
    double seen = 0.0;
    for (std::size_t b = 0; b < h.counts.size(); ++b) {
        seen += double(h.counts[b]);
        if (seen >= target) return h.lo + (double(b) + 0.5) * h.binWidth();
    }
    return h.hi;
}

// One line of the histogram drawn with eight bar heights, log scale.
std::string sparkline(const Histogram& h, int columns) {
    static const char* bars[] = {" ", "▁", "▂", "▃", "▄", "▅", "▆", "▇", "█"};
    std::vector<double> col(columns, 0.0);
    for (std::size_t b = 0; b < h.counts.size(); ++b) col[b * columns / h.counts.size()] += double(h.counts[b]);
    const double top = std::log1p(*std::max_element(col.begin(), col.end()));
    std::string out;
    for (double c : col) out += bars[top > 0 ? int(std::lround(8.0 * std::log1p(c) / top)) : 0];
    return out;
}

}  // namespace

int infoCommand(int argc, char** argv) {
    const std::vector<OptionSpec> specs = {{"bins", "N", "histogram bins (default 64)"},
                                           volumeCapOption(),
                                           {"help", "", "show this help"}};
    const Args args(specs, argc, argv, 2, "info");
    if (auto status = usageExit(args, args.positionals().size() != 1,
                                "usage: voxlab info DATASET [--bins N] [--max-volume-mib MIB]\n\n"
                                "Prints a volume's dimensions, voxel type, spacing, value range and histogram.\n"
                                "DATASET is a file (.nrrd .nhdr .fld .dat), a DICOM series (a folder, or one of\n"
                                "its files), or a phantom (phantom:NAME[:N]).\n\n",
                                specs))
        return *status;
    const Volume v = loadDatasetArgument(args);
    const int bins = args.get("bins") ? parseInt(*args.get("bins"), "--bins") : 64;
    if (bins < 1 || bins > 4096) throw Error("option --bins: must be in 1..4096");
    const Histogram h = v.histogram(bins);
    const glm::ivec3 d = v.dims();
    const glm::dvec3 s = v.spacing(), e = v.extent();
    std::printf("dataset:  %s\n", v.name().c_str());
    // What the loader knows of the source (a DICOM series: description, modality, slices, ...).
    for (const auto& [key, value] : v.metadata())
        std::printf("%-9s %s\n", (key + ":").c_str(), value.c_str());
    std::printf("dims:     %d x %d x %d (%zu voxels)\n", d.x, d.y, d.z, v.voxelCount());
    std::printf("type:     %s (%zu bytes/voxel, %.1f MiB)\n", voxelTypeName(v.type()), voxelTypeSize(v.type()),
                double(v.bytes().size()) / (1024.0 * 1024.0));
    if (v.streamed())
        std::printf("storage:  streamed from %s (over the %llu MiB volume cap: read as drawn)\n",
                    v.streamedFrom().c_str(), (unsigned long long)volumeCapMiB());
    std::printf("spacing:  %g %g %g\n", s.x, s.y, s.z);
    std::printf("extent:   %g x %g x %g\n", e.x, e.y, e.z);
    std::printf("range:    %g .. %g\n", v.minValue(), v.maxValue());
    std::printf("percentiles: 1%% %g, 50%% %g, 99%% %g\n", percentile(h, 0.01), percentile(h, 0.5),
                percentile(h, 0.99));
    std::uint64_t peak = 0;
    std::size_t peakBin = 0;
    for (std::size_t b = 0; b < h.counts.size(); ++b)
        if (h.counts[b] > peak) peak = h.counts[b], peakBin = b;
    std::printf("histogram (%d bins of %g, log scale; peak %llu voxels at %g):\n  |%s|\n  %-10g%*g\n", bins,
                h.binWidth(), (unsigned long long)peak, h.lo + (double(peakBin) + 0.5) * h.binWidth(),
                sparkline(h, std::min(bins, 64)).c_str(), h.lo, std::min(bins, 64) - 8, h.hi);
    return 0;
}

}  // namespace voxlab::cli
