#!/usr/bin/env bash
# The framework's module layering (tools/check_modules.py) holds, and the
# check catches a planted violation: a copy of framework/ in which the GL
# module includes the grader's header, one in which the volume module
# reaches into the renderer's private headers, and one in which a C++
# stage's contract (a stage folder's include/) includes the grader's.
# With a build folder, the modules' built libraries are checked too, a
# planted object that calls up (the lowest module calling the engine's
# module) is caught, and the compiler itself refuses an upward include: with
# the GL module's own flags (compile_commands.json), a file including the
# grader's header does not compile, and one including the io module's does.
# usage: check_modules.sh PROJECT_DIR [BUILD_DIR]
set -euo pipefail
project=$1
build=${2:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$project/tools/check_modules.py" "$project" ${build:+--objects "$build"}

plant() {  # plant FILE LINE EXPECTED
    rm -rf "$work/p" && mkdir -p "$work/p" && cp -r "$project/framework" "$work/p/"
    echo "$2" >> "$work/p/$1"
    if out=$(/usr/bin/python3 "$project/tools/check_modules.py" "$work/p"); then
        echo "FAIL: a planted violation ($1: $2) passed"; exit 1
    fi
    grep -qF "$3" <<< "$out" || { echo "FAIL: the planted violation is not named: $out"; exit 1; }
    echo "ok    planted in $1, caught: $(grep -F "$3" <<< "$out" | head -1)"
}
plant framework/src/gl/shader.cpp '#include "voxlab/grading.h"' "framework/src/gl/shader.cpp"
plant framework/include/volume/voxlab/volume.h '#include "../render/engine_internal.h"' "module volume includes ../render/engine_internal.h"
plant framework/stages/splat/include/voxlab/splatting.h '#include "voxlab/grading.h"' "module contracts includes grading.h"

if [ -n "$build" ]; then
    # The io module's library, with one more member that calls the render
    # module's defaultImplementationRoot(): its header is never included, as
    # a hand-written declaration would do it.
    mkdir -p "$work/b/framework"
    cp "$build"/framework/libvoxlab_*.a "$work/b/framework/"
    printf '#include <string>\nnamespace voxlab { std::string defaultImplementationRoot(); }\n%s\n' \
        'std::string plantedCaller() { return voxlab::defaultImplementationRoot(); }' > "$work/planted.cpp"
    c++ -c "$work/planted.cpp" -o "$work/planted.o"
    ar r "$work/b/framework/libvoxlab_io.a" "$work/planted.o" 2>/dev/null
    if out=$(/usr/bin/python3 "$project/tools/check_modules.py" "$project" --objects "$work/b"); then
        echo "FAIL: a planted upward call passed the object check"; exit 1
    fi
    expected="libvoxlab_io.a(planted.o): module io uses voxlab::defaultImplementationRoot[abi:cxx11]() (module render"
    grep -qF "$expected" <<< "$out" || { echo "FAIL: the planted call is not named: $out"; exit 1; }
    echo "ok    planted in libvoxlab_io.a, caught: $(grep -F "$expected" <<< "$out" | head -1)"

    # The compiler: the GL module sees its own headers and io's, not the grader's.
    flags=$(/usr/bin/python3 - "$build/compile_commands.json" <<'PY'
import json, shlex, sys
for entry in json.load(open(sys.argv[1])):
    if entry["file"].endswith("/framework/src/gl/shader.cpp"):
        words = shlex.split(entry["command"])
        print(" ".join(shlex.quote(w) for w in words if w.startswith(("-I", "-isystem", "-D", "-std"))))
        break
PY
)
    [ -n "$flags" ] || { echo "FAIL: no compile command for framework/src/gl/shader.cpp in $build"; exit 1; }
    printf '#include "voxlab/error.h"\n' > "$work/allowed.cpp"
    eval c++ $flags -fsyntax-only "$work/allowed.cpp" || { echo "FAIL: the GL module cannot include io's header"; exit 1; }
    printf '#include "voxlab/grading.h"\n' > "$work/upward.cpp"
    if out=$(eval c++ $flags -fsyntax-only "$work/upward.cpp" 2>&1); then
        echo "FAIL: the GL module's flags compile an include of the grader's header"; exit 1
    fi
    grep -qF "voxlab/grading.h: No such file" <<< "$out" || { echo "FAIL: not refused as missing: $out"; exit 1; }
    echo "ok    the compiler refuses the GL module an include of the grader's header"
fi
