#!/usr/bin/env bash
# voxlab installed, and voxlab moved: neither needs the checkout it was built
# from, nor $VOXLAB_ROOT (voxlab/project_root.h, framework/install.cmake).
#
# 1. `cmake --install` into a prefix, then the prefix moved elsewhere (nothing
#    in it may name where it was installed). From an unrelated folder the
#    installed voxlab renders a bundled dataset by name, and grades a C++
#    stage of the installed reference at full marks.
# 2. The checkout's files and its programs copied to another folder, as a
#    course copies a tree to its machines: the copy grades the C++ stage.
# In each, one header of the copy is then poisoned with an #error: the C++
# stage must now fail to build, naming it, which shows that the stage was
# compiled against the copy's headers and not the original checkout's.
# With --deb instead (CTest `deb_package`, heavy: packing takes minutes):
# 3. The .deb (cpack -G DEB): its control names the libraries voxlab links
#    and what grading C++ needs; unpacked (dpkg-deb -x, not installed into
#    the machine) its voxlab renders and grades the C++ stage at full marks.
#
# usage: check_install.sh PROJECT_DIR BUILD_DIR [--deb]
set -euo pipefail
project=$1
build=$2
deb=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset VOXLAB_ROOT VOXLAB_DATA_PATH VOXLAB_EXPECTED_CACHE
export XDG_CACHE_HOME="$work/cache"
stage=texslice2d

fail() { echo "FAIL: $*"; exit 1; }

# grade ROOT NAME: grades ROOT's reference stage from an unrelated folder;
# prints the stage's score and max_score.
grade() {
    local root=$1 name=$2
    mkdir -p "$work/elsewhere/$name"
    (cd "$work/elsewhere/$name" &&
     "$root/bin/voxlab" grade --submission "$3" --stage "$stage" --out report --jobs 1 --quiet \
        > log.txt 2>&1) || true
    /usr/bin/python3 - "$work/elsewhere/$name/report/results.json" <<'PY'
import json, sys
try:
    r = json.load(open(sys.argv[1]))
    t = r.get("tests", [])
    print(sum(x.get("score", 0) for x in t), sum(x.get("max_score", 0) for x in t))
except Exception as e:
    print("none none")
PY
}

full_marks() {  # full_marks WHAT "SCORE MAX"
    read -r score max <<< "$2"
    [ "$score" != none ] && [ "$max" != 0 ] && /usr/bin/python3 -c "import sys; sys.exit(abs($score - $max) > 1e-9)" ||
        fail "$1: $stage scored $score of $max ($(tail -3 "$work/elsewhere/$3/log.txt" 2>/dev/null))"
    echo "ok    $1: $stage graded $score of $max"
}

poisoned_fails() {  # poisoned_fails WHAT HEADER ROOT_BIN SUBMISSION NAME
    echo '#error voxlab-poisoned-copy' >> "$2"
    read -r score max <<< "$(grade "$3" "$5" "$4")"
    [ "$score" = none ] || [ "$score" != "$max" ] || fail "$1: full marks with a poisoned header"
    # The grader refuses a reference whose C++ stages do not compile, naming
    # the header; the message must name the copy's.
    grep -rqsF "$2" "$work/elsewhere/$5" && grep -rqs 'voxlab-poisoned-copy' "$work/elsewhere/$5" ||
        fail "$1: the stage was not compiled against the copy's headers ($(tail -2 "$work/elsewhere/$5/log.txt"))"
    echo "ok    $1: a poisoned header in the copy stops the C++ stage's build, naming the copy's header"
}

# 3. The .deb, unpacked.
if [ "$deb" = --deb ]; then
    (cd "$build" && cpack -G DEB -B "$work/deb" > "$work/cpack.log" 2>&1) || fail "cpack: $(tail -3 "$work/cpack.log")"
    package=$(ls "$work"/deb/voxlab_*.deb)
    control=$(dpkg-deb -f "$package" Package Section Depends)
    for want in "Package: voxlab" "Section: education" g++ libglm-dev nlohmann-json3-dev libosmesa6 libegl1 \
                libglfw3 libgdcm3.0 libseccomp2 libarchive13 libstb0 zlib1g; do
        grep -qF -- "$want" <<< "$control" || fail "the .deb's control lacks $want: $control"
    done
    echo "ok    the .deb's control: $(grep Depends <<< "$control" | cut -c1-110)..."
    dpkg-deb -x "$package" "$work/unpacked"
    prefix="$work/unpacked/usr"
    mkdir -p "$work/elsewhere/deb-render"
    (cd "$work/elsewhere/deb-render" &&
     "$prefix/bin/voxlab" render --dataset bucky.nrrd --renderer mip --size 64x64 --out bucky.png > log.txt 2>&1) ||
        fail "the .deb's voxlab does not render: $(tail -2 "$work/elsewhere/deb-render/log.txt")"
    [ -s "$work/elsewhere/deb-render/bucky.png" ] || fail "the .deb's voxlab wrote no image"
    echo "ok    the .deb's voxlab, unpacked, renders bucky.nrrd by name from another folder"
    full_marks "the .deb" "$(grade "$prefix" deb "$prefix/share/voxlab/reference")" deb
    exit 0
fi

# 1. Installed, then the prefix moved.
cmake --install "$build" --prefix "$work/installed" > "$work/install.log" ||
    fail "cmake --install: $(tail -3 "$work/install.log")"
share=share/voxlab
for f in bin/voxlab bin/voxlab-stage-host $share/shaders/voxlab/ray.glsl $share/datasets/bucky.nrrd \
         $share/framework/include/io/voxlab/error.h $share/framework/include/mesh/voxlab/stage_contracts.h \
         $share/framework/stages/$stage/include/voxlab/slice_axis.h $share/framework/stage_library/stage_exports.o \
         $share/framework/stage_library/prelude/voxlab_stage_prelude.h.gch $share/reference/$stage/grading.json \
         $share/assignments/$stage/grading.json; do
    [ -f "$work/installed/$f" ] || fail "the install has no $f"
done
echo "ok    the install holds the programs, the project root and the C++ stages' headers and prebuilt objects"
mv "$work/installed" "$work/moved-prefix"
prefix="$work/moved-prefix"
mkdir -p "$work/elsewhere/render"
(cd "$work/elsewhere/render" &&
 "$prefix/bin/voxlab" render --dataset bucky.nrrd --renderer mip --size 64x64 --out bucky.png > log.txt 2>&1) ||
    fail "the installed voxlab does not render a bundled dataset: $(tail -2 "$work/elsewhere/render/log.txt")"
[ -s "$work/elsewhere/render/bucky.png" ] || fail "the installed voxlab wrote no image"
echo "ok    the installed voxlab, moved, renders bucky.nrrd by name from another folder"
full_marks "installed" "$(grade "$prefix" installed "$prefix/$share/reference")" installed
poisoned_fails "installed" "$prefix/$share/framework/stages/$stage/include/voxlab/slice_axis.h" "$prefix" \
    "$prefix/$share/reference" installed-poisoned

# 2. A copied checkout: its project files and its build's programs.
copy="$work/copied-checkout"
mkdir -p "$copy/build/bin" "$copy/framework"
cp -r "$project/shaders" "$project/datasets" "$project/reference" "$project/assignments" "$copy/"
cp -r "$project/framework/include" "$project/framework/stage_library" "$project/framework/stages" "$copy/framework/"
cp "$build/bin/voxlab" "$build/bin/voxlab-stage-host" "$copy/build/bin/"
full_marks "copied checkout" "$(grade "$copy/build" copied "$copy/reference")" copied
poisoned_fails "copied checkout" "$copy/framework/stages/$stage/include/voxlab/slice_axis.h" "$copy/build" \
    "$copy/reference" copied-poisoned
