#!/usr/bin/python3
"""The framework's modules and the includes between them.

A module is a folder of framework/src/ (the CLI, framework/cli/, is the
module "cli"; the stage folders, framework/stages/*/, are the module
"stages"). A header framework/include/voxlab/NAME.h belongs to the
module whose folder holds NAME.cpp; a header with no such file is assigned
below (HEADERS). A stage's C++ contract,
framework/stages/STAGE/include/voxlab/NAME.h, belongs to "contracts" (the
generated voxlab/stage_contracts.h that includes them all, to "mesh"). Each module declares the modules it may include
(DEPENDS, lowest first); a file that includes a header of any other module
is a violation, and this prints each as FILE: includes HEADER (MODULE), then
fails. KNOWN lists the violations still to be removed, each with why; one
that is gone must be taken off the list (so the list only shrinks).

usage: check_modules.py PROJECT_DIR [--graph]
"""
import os
import re
import sys

DEPENDS = {
    "io": [],                        # errors, files, numbers, the project root
    "image": ["io"],                 # images, PNG, metrics
    "volume": ["io"],                # volumes, loaders, phantoms, the camera
    "gl": ["io"],                    # contexts, shaders, the stubs in a stage's text
    "scene": ["volume", "image", "io"],              # scenes, transfer functions, labels
    "contracts": ["scene", "volume", "io"],          # the C++ stages' contracts (stage folders' include/)
    "mesh": ["contracts", "scene", "volume", "io"],  # the C++ stage table and stage libraries
    "render": ["gl", "mesh", "contracts", "scene", "volume", "image", "io"],  # the engine
    "renderers": ["render", "gl", "mesh", "contracts", "scene", "volume", "image", "io"],
    "grade": ["renderers", "render", "gl", "mesh", "contracts", "scene", "volume", "image", "io"],
    "stages": ["grade", "renderers", "render", "gl", "mesh", "contracts", "scene", "volume", "image", "io"],
    "window": ["renderers", "render", "gl", "mesh", "contracts", "scene", "volume", "image", "io"],
    "cli": ["window", "grade", "renderers", "render", "gl", "mesh", "contracts", "scene", "volume", "image", "io"],
}

# Headers without a .cpp of the same name.
HEADERS = {
    "error": "io",
    "image": "image",
    "renderers": "renderers",
    "window": "window",
}

# Violations left, each with its reason; remove an entry with its violation.
KNOWN = {}


def module_of_source(project, path):
    rel = os.path.relpath(path, project)
    parts = rel.split(os.sep)
    if parts[:2] == ["framework", "cli"]:
        return "cli"
    if parts[:2] == ["framework", "src"]:
        return parts[2]
    if parts[:2] == ["framework", "stages"]:
        return "contracts" if parts[3:5] == ["include", "voxlab"] else "stages"
    return None


def header_modules(project):
    found = {}
    src = os.path.join(project, "framework", "src")
    for module in sorted(os.listdir(src)):
        for name in os.listdir(os.path.join(src, module)):
            if name.endswith(".cpp"):
                found.setdefault(name[:-4], module)
    found.update(HEADERS)
    stages = os.path.join(project, "framework", "stages")
    for stage in sorted(os.listdir(stages)):
        contracts = os.path.join(stages, stage, "include", "voxlab")
        if os.path.isdir(contracts):
            for name in os.listdir(contracts):
                if name.endswith(".h"):
                    found[name[:-2]] = "contracts"
    found["stage_contracts"] = "mesh"  # generated from the contracts, for the stage table
    return found


def files(project):
    for top in ("framework/src", "framework/cli", "framework/stages", "framework/include/voxlab"):
        for root, _, names in os.walk(os.path.join(project, top)):
            for n in sorted(names):
                if n.endswith((".cpp", ".h")):
                    yield os.path.join(root, n)


def main():
    project = sys.argv[1]
    modules = header_modules(project)
    problems, unknown, seen_known = [], [], set()
    edges = set()
    for path in files(project):
        rel = os.path.relpath(path, project)
        if rel.startswith("framework/include/"):
            base = os.path.splitext(os.path.basename(path))[0]
            module = modules.get(base)
            if module is None:
                unknown.append(f"{rel}: no module (no {base}.cpp under framework/src/; add it to HEADERS)")
                continue
        else:
            module = module_of_source(project, path)
        if module not in DEPENDS:
            unknown.append(f"{rel}: module '{module}' is not declared in DEPENDS")
            continue
        with open(path, encoding="utf-8", errors="replace") as f:
            for number, line in enumerate(f, 1):
                m = re.match(r'\s*#\s*include\s+"voxlab/([^"]+)\.h"', line)
                private = re.match(r'\s*#\s*include\s+"\.\./([a-z_]+)/([^"]+)"', line)
                if not m and not private:
                    continue
                target = modules.get(m.group(1)) if m else private.group(1)
                name = m.group(1) + ".h" if m else f"../{private.group(1)}/{private.group(2)}"
                if target is None or target == module:
                    continue
                edges.add((module, target))
                if target in DEPENDS[module]:
                    continue
                key = (rel, name)
                if key in KNOWN:
                    seen_known.add(key)
                    continue
                problems.append(f"{rel}:{number}: module {module} includes {name} "
                                f"(module {target}, not among its dependencies {DEPENDS[module]})")
    stale = [f"{f} -> {h}: listed in KNOWN but no longer there; take it off" for (f, h) in KNOWN
             if (f, h) not in seen_known]
    if "--graph" in sys.argv:
        for a, b in sorted(edges):
            print(f"{a} -> {b}")
    for p in unknown + problems + stale:
        print(p)
    known = len(seen_known)
    print(f"check_modules: {len(DEPENDS)} modules, {len(edges)} dependencies used, "
          f"{len(problems) + len(unknown) + len(stale)} problem(s), {known} known violation(s) left")
    return 1 if problems or unknown or stale else 0


if __name__ == "__main__":
    sys.exit(main())
