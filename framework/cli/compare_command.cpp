// voxlab compare: how far apart two images are, by the grader's metrics.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "voxlab/error.h"
#include "voxlab/image.h"
#include "voxlab/image_metrics.h"

namespace voxlab::cli {

int compareCommand(int argc, char** argv) {
    const std::vector<OptionSpec> specs = {
        {"threshold", "T", "grey levels (of 255) above which a pixel counts as different (default 2)"},
        {"diff", "FILE.png", "also write the difference |A - B| per channel, times 4 (black: equal)"},
        {"help", "", "show this help"}};
    const Args args(specs, argc, argv, 2, "compare");
    if (auto status = usageExit(args, args.positionals().size() != 2,
                                "usage: voxlab compare A.png B.png [--threshold T] [--diff FILE.png]\n\n"
                                "Compares two images of the same size (for example your render and a golden image in\n"
                                "tests/golden/images/) and prints the largest and mean per-pixel difference, the share\n"
                                "of pixels above the threshold, PSNR and SSIM (mean and worst window).\n\n",
                                specs))
        return *status;
    const double threshold = args.get("threshold") ? parseNumber(*args.get("threshold"), "--threshold") : 2.0;
    if (!(threshold >= 0.0 && threshold <= 255.0)) throw Error("option --threshold: must be in 0..255");
    const Image a = loadPng(args.positionals()[0]), b = loadPng(args.positionals()[1]);
    const PixelDifference d = pixelDifference(a, b, threshold / 255.0);
    const double p = psnr(a, b);
    const SsimResult s = ssim(a, b);
    std::printf("max difference:   %.2f grey levels\n", d.max * 255.0);
    std::printf("mean difference:  %.3f grey levels\n", d.mean * 255.0);
    std::printf("above %-5g levels: %.3f%% of pixels\n", threshold, d.fractionAbove * 100.0);
    if (std::isinf(p)) std::printf("PSNR:             inf (identical)\n");
    else std::printf("PSNR:             %.2f dB\n", p);
    std::printf("SSIM:             %.5f (worst window %.5f)\n", s.mean, s.min);
    if (auto out = args.get("diff")) {
        Image diff(a.width, a.height);
        for (std::size_t i = 0; i < diff.rgba.size(); ++i)
            diff.rgba[i] = i % 4 == 3 ? 1.0f : std::min(1.0f, 4.0f * std::abs(a.rgba[i] - b.rgba[i]));
        savePng(diff, *out);
        std::printf("difference (x4): %s\n", out->c_str());
    }
    return 0;
}

}  // namespace voxlab::cli
