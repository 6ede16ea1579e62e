#!/usr/bin/python3
"""The framework's modules, the includes between them and their symbols.

A module is a folder of framework/src/ (the CLI, framework/cli/, is the
module "cli"; the stage folders, framework/stages/, are the module
"stages"), built as the static library voxlab_MODULE. framework/modules.cmake
declares each module and the modules it uses (DEPENDS); here, a module may
use those and, through them, theirs.

A header framework/include/MODULE/voxlab/NAME.h belongs to MODULE (the
build gives each module's library that folder, so the compiler refuses an
include from a module not among its dependencies; this check names it). A
stage's C++ contract, framework/stages/STAGE/include/voxlab/NAME.h, belongs
to "contracts" (the generated voxlab/stage_contracts.h that includes them
all, to "mesh"). Tests (test_*.cpp) use the whole framework and are not
checked. A file that includes a header of a module its own does not use is
a violation, printed as FILE: includes HEADER (MODULE). KNOWN lists the
violations still to be removed, each with why; one that is gone must be
taken off the list (so the list only shrinks).

With --objects BUILD_DIR, the modules' built libraries
(BUILD_DIR/framework/libvoxlab_MODULE.a) are checked as well: a symbol one
uses that another module defines must come from a module it uses. This is
what a lower module calling up looks like once compiled, whatever its
includes say (a declaration written by hand, a macro).

usage: check_modules.py PROJECT_DIR [--graph] [--objects BUILD_DIR]
"""
import os
import re
import subprocess
import sys


def declared_modules(project):
    """framework/modules.cmake: {module: [modules it uses, directly]}, in order."""
    direct = {}
    path = os.path.join(project, "framework", "modules.cmake")
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = re.match(r"\s*voxlab_module\(\s*([a-z_]+)((?:\s+DEPENDS(?:\s+[a-z_]+)+)?)\s*\)", line)
            if m:
                deps = m.group(2).split()[1:]
                for d in deps:
                    if d not in direct:
                        raise SystemExit(f"{path}: module {m.group(1)} uses {d}, which is not declared above it")
                direct[m.group(1)] = deps
    return direct


def closure(direct):
    """{module: every module it uses, directly or through another}."""
    result = {}
    for module, deps in direct.items():  # declared lowest first
        found = []
        for d in deps:
            for m in [d] + result[d]:
                if m not in found:
                    found.append(m)
        result[module] = found
    return result


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
        if parts[-1].startswith("test_"):
            return None  # a test: the whole framework
        if parts[-1] == "command.cpp":
            return "cli"  # a command a stage brings is built into the program
        if parts[-1] == "section.cpp":
            return "scene"  # a scene section a stage brings is read with the scene
        return "contracts" if parts[3:5] == ["include", "voxlab"] else "stages"
    return None


def header_modules(project):
    found = {}
    include = os.path.join(project, "framework", "include")
    for module in sorted(os.listdir(include)):
        folder = os.path.join(include, module, "voxlab")
        for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
            if name.endswith(".h"):
                found[name[:-2]] = module
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
    for top in ("framework/src", "framework/cli", "framework/stages", "framework/include"):
        for root, _, names in os.walk(os.path.join(project, top)):
            for n in sorted(names):
                if n.endswith((".cpp", ".h")):
                    yield os.path.join(root, n)


def symbols(archive):
    """(defined, used) of a static library: {symbol: member} for the
    symbols its members define strongly, and [(member, symbol)] for those
    they use without defining."""
    out = subprocess.run(["nm", "-A", "-P", "-g", archive], capture_output=True, text=True, check=True).stdout
    defined, used = {}, []
    for line in out.splitlines():
        m = re.match(r"\S+\[(\S+)\]: (\S+) ([A-Za-z])", line)
        if not m:
            continue
        member, name, kind = m.groups()
        if kind == "U":
            used.append((member, name))
        elif kind in "TDBR":  # not weak (W, V): inline code every user has a copy of
            defined.setdefault(name, member)
    return defined, used


def demangle(name):
    out = subprocess.run(["c++filt", name], capture_output=True, text=True)
    return out.stdout.strip() or name


def object_problems(build, depends):
    """What each module's library uses from a module it does not use, and
    the module pairs that one library's symbols connect."""
    libraries = {m: os.path.join(build, "framework", f"libvoxlab_{m}.a") for m in depends}
    libraries = {m: path for m, path in libraries.items() if os.path.isfile(path)}
    if not libraries:
        return [f"{build}/framework: no libvoxlab_MODULE.a (is it a build folder, built?)"], set()
    owner, uses = {}, {}
    for module, path in libraries.items():
        defined, used = symbols(path)
        for name in defined:
            owner.setdefault(name, module)
        uses[module] = used
    problems, edges = [], set()
    for module, used in uses.items():
        for member, name in used:
            target = owner.get(name)
            if target is None or target == module:
                continue
            edges.add((module, target))
            if target not in depends[module]:
                problems.append(f"libvoxlab_{module}.a({member}): module {module} uses {demangle(name)} "
                                f"(module {target}, not among its dependencies {depends[module]})")
    return problems, edges


def include_problems(project, depends):
    modules = header_modules(project)
    problems, unknown, seen_known = [], [], set()
    edges = set()
    for path in files(project):
        rel = os.path.relpath(path, project)
        if rel.startswith("framework/include/"):
            module = rel.split("/")[2]
        else:
            module = module_of_source(project, path)
            if module is None:
                continue
        if module not in depends:
            unknown.append(f"{rel}: module '{module}' is not declared in framework/modules.cmake")
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
                if target in depends[module]:
                    continue
                key = (rel, name)
                if key in KNOWN:
                    seen_known.add(key)
                    continue
                problems.append(f"{rel}:{number}: module {module} includes {name} "
                                f"(module {target}, not among its dependencies {depends[module]})")
    stale = [f"{f} -> {h}: listed in KNOWN but no longer there; take it off" for (f, h) in KNOWN
             if (f, h) not in seen_known]
    return unknown + problems + stale, edges, len(seen_known)


def main():
    project = sys.argv[1]
    depends = closure(declared_modules(project))
    problems, edges, known = include_problems(project, depends)
    linked = None
    if "--objects" in sys.argv:
        object_list, linked = object_problems(sys.argv[sys.argv.index("--objects") + 1], depends)
        problems += object_list
    if "--graph" in sys.argv:
        for a, b in sorted(edges):
            print(f"{a} -> {b}")
    for p in problems:
        print(p)
    objects = "" if linked is None else f", {len(linked)} used between the libraries"
    print(f"check_modules: {len(depends)} modules, {len(edges)} dependencies included{objects}, "
          f"{len(problems)} problem(s), {known} known violation(s) left")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
