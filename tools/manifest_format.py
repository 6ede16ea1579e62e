"""Writes a stage manifest (reference/<stage>/grading.json) in the project's
layout: top-level keys one per line, one scene, check or hint per line.
Used by tools/mutant_hints.py; keeps hand edits and generated hints in one
readable style."""
import json

ORDER = ["title", "order", "points", "about", "functions", "requires", "conditions", "files", "cpp_functions",
         "scenes", "checks", "hints"]


def dumps(manifest):
    keys = [k for k in ORDER if k in manifest] + [k for k in manifest if k not in ORDER]
    lines = []
    for k in keys:
        v = manifest[k]
        if isinstance(v, list) and v and isinstance(v[0], dict):
            items = ",\n".join("    " + json.dumps(item, ensure_ascii=False) for item in v)
            lines.append(f'  {json.dumps(k)}: [\n{items}\n  ]')
        else:
            lines.append(f'  {json.dumps(k)}: {json.dumps(v, ensure_ascii=False)}')
    return "{\n" + ",\n".join(lines) + "\n}\n"


def write(path, manifest):
    with open(path, "w", encoding="utf-8") as f:
        f.write(dumps(manifest))
