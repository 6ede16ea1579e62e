#!/usr/bin/python3
"""Compile cost of two build trees, source by source.

Compiles a random sample of the sources both trees' compile_commands.json
name (the same path relative to each tree's root), alternating between the
trees so that the machine's drift falls on both, output to /dev/null, and
prints the total seconds of each. A whole build's wall time mixes this with
the build's ordering and linking; this isolates what the compiler pays.

usage: compile_cost.py OLD_ROOT OLD_BUILD NEW_ROOT NEW_BUILD [SAMPLE] [SEED]
"""
import json
import os
import random
import re
import subprocess
import sys
import time


def commands(root, build):
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as f:
        return {os.path.relpath(e["file"], root): e for e in json.load(f)}


def seconds(entry):
    command = re.sub(r" -o \S+", " -o /dev/null", entry["command"])
    start = time.monotonic()
    done = subprocess.run(command, shell=True, cwd=entry["directory"],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if done.returncode != 0:
        sys.exit(f"compile_cost: {entry['file']} does not compile")
    return time.monotonic() - start


def main():
    if len(sys.argv) not in (5, 6, 7):
        sys.exit(__doc__.strip().splitlines()[-1])
    old, new = commands(*sys.argv[1:3]), commands(*sys.argv[3:5])
    sample_size = int(sys.argv[5]) if len(sys.argv) > 5 else 30
    random.seed(int(sys.argv[6]) if len(sys.argv) > 6 else 3)
    common = sorted(set(old) & set(new))
    sample = random.sample(common, min(sample_size, len(common)))
    total_old = total_new = 0.0
    for path in sample:
        total_new += seconds(new[path])
        total_old += seconds(old[path])
    print(f"{len(common)} sources in both ({len(set(new) - set(old))} only new, "
          f"{len(set(old) - set(new))} only old); {len(sample)} compiled: "
          f"old {total_old:.1f} s, new {total_new:.1f} s")


if __name__ == "__main__":
    main()
