#!/usr/bin/python3
"""Summarises a grading report.json: per stage its score, the worst
tolerance ratio over its scenes (1.0 = at a bound; above 1 fails) and the
item that set it, and every item that did not pass.

  bench/grade_summary.py REPORT_DIR_OR_JSON

A scene's ratio is its largest of: pixels off / max_fraction, largest patch
/ max_cluster, mean FLIP / max_flip, (1 - SSIM) / (1 - min_ssim). Used by
bench/gpu_check.sh and for grading on softpipe (docs/grading.md)."""
import json
import os
import sys


def scene_ratio(scene):
    m, t = scene.get("metrics", {}), scene.get("tolerance", {})
    ratios = []
    for metric, bound in (("fraction_over", "max_fraction"), ("largest_cluster", "max_cluster"),
                          ("flip_mean", "max_flip")):
        if metric in m and t.get(bound):
            ratios.append(m[metric] / t[bound])
    if "ssim" in m and t.get("min_ssim", 1.0) < 1.0:
        ratios.append((1.0 - m["ssim"]) / (1.0 - t["min_ssim"]))
    return max(ratios) if ratios else 0.0


def main():
    path = sys.argv[1]
    if os.path.isdir(path):
        path = os.path.join(path, "report.json")
    report = json.load(open(path))
    print("machine: %s" % report.get("machine", "?"))
    print("| stage | score | worst ratio | at |")
    print("|---|---|---|---|")
    failing = []
    for stage in report.get("stages", []):
        worst, at = 0.0, ""
        for scene in stage.get("scenes", []):
            r = scene_ratio(scene)
            if r > worst:
                worst, at = r, scene["name"]
            if scene.get("status") != "passed":
                failing.append("%s/%s: %s" % (stage["stage"], scene["name"], scene.get("message", "")))
        for check in stage.get("checks", []):
            if check.get("status") != "passed":
                failing.append("%s/%s: %s" % (stage["stage"], check["name"], check.get("message", "")))
        print("| %s | %.2f / %g | %.2f | %s |" % (stage["stage"], stage.get("score", 0), stage.get("max_score", 0),
                                                 worst, at))
    print("total %.2f / %g" % (report.get("score", 0), report.get("max_score", 0)))
    for f in failing:
        print("not passed: " + f)


if __name__ == "__main__":
    main()
