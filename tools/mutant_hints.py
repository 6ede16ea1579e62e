#!/usr/bin/env python3
"""Writes the "hints" of each stage manifest (reference/<stage>/grading.json)
from the mutant suite: a mutant's signature is the set of its stage's items
(scenes and function checks) that it fails; a submission that fails exactly
that set is shown the mutant's hint, the misconception in the student's own
terms ("Looks like ..."). Hints never hold solution code.

Usage:
  VOXLAB_MUTANT_SIGNATURES=/tmp/signatures.json \\
      build/tests/test_grader_mutants --gtest_filter=MutantSuite.TheGraderFailsEveryMutant
  /usr/bin/python3 tools/mutant_hints.py /tmp/signatures.json
  /usr/bin/python3 tools/make_assignments.py

A signature shared by several mutants gets all their hints (the report shows
up to three). A signature that fails every item of a stage says little about
the cause, so it gets no hint.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import manifest_format  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: mutant_hints.py SIGNATURES.json (see the top of this file)")
    signatures = json.load(open(sys.argv[1], encoding="utf-8"))["signatures"]
    mutants = []
    for stage in sorted(os.listdir(os.path.join(ROOT, "reference"))):
        path = os.path.join(ROOT, "reference", stage, "mutants.json")
        if os.path.exists(path):
            mutants += json.load(open(path, encoding="utf-8")).get("mutants", [])
    hint_of = {m["name"]: m.get("hint", "") for m in mutants}
    per_stage = {}
    for s in signatures:
        hint = hint_of.get(s["mutant"], "")
        if not hint or not s["failed"]:
            continue
        per_stage.setdefault(s["stage"], {}).setdefault(tuple(sorted(s["failed"])), []).append(hint)
    for stage, table in sorted(per_stage.items()):
        path = os.path.join(ROOT, "reference", stage, "grading.json")
        manifest = json.load(open(path, encoding="utf-8"))
        every = {i["name"] for i in manifest.get("scenes", []) + manifest.get("checks", [])}
        hints = [{"failed": list(failed), "hints": list(dict.fromkeys(texts))}
                 for failed, texts in sorted(table.items()) if set(failed) != every]
        if hints:
            manifest["hints"] = hints
        else:
            manifest.pop("hints", None)
        manifest_format.write(path, manifest)
        print(f"{stage}: {len(hints)} signatures with hints")


if __name__ == "__main__":
    main()
