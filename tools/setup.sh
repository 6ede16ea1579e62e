#!/usr/bin/env bash
# voxlab set-up, from a fresh Debian 12 machine to a running program.
#
#   tools/setup.sh          install what is missing, build what the main job
#                           needs (the voxlab program and the stage host it
#                           runs), and run it: the viewer on the default
#                           scene when a display is available, else a
#                           headless render of the default scene to a PNG
#                           whose path it prints.
#   tools/setup.sh --test   the same set-up, then builds everything (the
#                           tests, the fuzzers, the benchmarks) and runs the
#                           test suite (tests labelled "heavy" too with
#                           --test-all).
#   tools/setup.sh --web    the same set-up, then the browser workbench:
#                           tools/setup_web.sh builds it into build-web/site
#                           (docs/web.md).
#   tools/setup.sh --grader only what grading needs (an autograder image:
#                           tools/gradescope/): the packages for headless
#                           rendering and the voxlab program, no viewer and
#                           no tests.
#
# Debian 12 and Ubuntu 22.04 (Gradescope's base image) name every package
# the same; on Ubuntu most of them are in the "universe" component. A
# package that apt cannot find stops the set-up with one line naming it.
#
# Environment: VOXLAB_BUILD_DIR (default: build), VOXLAB_JOBS (default: nproc).
# For tests: VOXLAB_OS_RELEASE (another os-release file), and
# VOXLAB_SETUP_DRY_RUN=1, which prints the system, its package list and the
# missing packages, checks that apt offers them, and stops there.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${VOXLAB_BUILD_DIR:-$root/build}"
jobs="${VOXLAB_JOBS:-$(nproc 2>/dev/null || echo 2)}"
mode="${1:-run}"
case "$mode" in
  run|--test|--test-all|--grader|--web) ;;
  -h|--help) sed -n '/^set -euo/q; 2,$p' "$0"; exit 0 ;;
  *) echo "setup.sh: unknown argument '$mode' (expected --test, --test-all, --web, --grader or nothing)" >&2; exit 2 ;;
esac

# 1. System packages, by the names Debian 12 and Ubuntu 22.04 share. Only the
#    missing ones are installed.
os_release="${VOXLAB_OS_RELEASE:-/etc/os-release}"
os_field() { sed -n "s/^$1=//p" "$os_release" 2>/dev/null | head -n 1 | tr -d "\"'"; }
distro=$(os_field ID) distro_version=$(os_field VERSION_ID)
system="${distro:-unknown} ${distro_version:-?}"
case "$system" in
  "debian 12"|"ubuntu 22.04") ;;
  *) echo "setup: $system is untested (Debian 12 and Ubuntu 22.04 are); trying their package names" >&2 ;;
esac
# libgdcm-dev reads DICOM series (every mode loads volumes); libarchive-dev
# unpacks students' zip uploads for the grader; python3-pydicom (with
# python3-numpy, which it only recommends and we install without
# recommends) writes the DICOM series the tests load (tests/dicom/make_series.py);
# glslang-tools checks every shader as GLSL ES 3.00 too (tests/test_glsl_es.cpp);
# dpkg-dev lets cpack find the .deb's Depends (dpkg-shlibdeps; the test deb_package).
packages=(cmake make g++ pkg-config python3 libglm-dev libstb-dev libosmesa6-dev libegl-dev zlib1g-dev
          nlohmann-json3-dev khronos-api libgdcm-dev libseccomp-dev libarchive-dev)
[ "$mode" = --grader ] || packages+=(libglfw3-dev libimgui-dev libgtest-dev xvfb xauth fonts-dejavu-core
                                     python3-pydicom python3-numpy glslang-tools dpkg-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Stops with one line naming every package of "$@" that apt has no candidate for.
require_available() {
  local p policy candidate='Candidate: [^(]' unavailable=() hint=""
  for p in "$@"; do
    policy=$(LC_ALL=C apt-cache policy "$p" 2>/dev/null || true)
    [[ $policy =~ $candidate ]] || unavailable+=("$p")
  done
  [ ${#unavailable[@]} -eq 0 ] && return 0
  [ "$distro" = ubuntu ] && hint=" (on Ubuntu, enable the 'universe' component)"
  echo "setup: not available from apt on $system: ${unavailable[*]}$hint" >&2
  exit 1
}
if [ -n "${VOXLAB_SETUP_DRY_RUN:-}" ]; then
  echo "setup: $system: ${packages[*]}"
  echo "setup: missing: ${missing[*]:-none}"
  [ ${#missing[@]} -eq 0 ] || require_available "${missing[@]}"
  exit 0
fi
if [ ${#missing[@]} -gt 0 ]; then
  if ! command -v apt-get >/dev/null; then
    echo "setup: no apt-get on $system: install these by hand: ${missing[*]}" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  require_available "${missing[@]}"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# 2. Configure and build.
if [ "$mode" = --grader ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVOXLAB_BUILD_TESTS=OFF -DVOXLAB_WITH_VIEWER=OFF >/dev/null
  cmake --build "$build" -j "$jobs" --target voxlab
else
  # Configured for the tests too (so that --test later only builds more),
  # but only the --test modes build them: the main job needs the voxlab
  # program (its target builds the stage host it runs beside it).
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVOXLAB_BUILD_TESTS=ON -DVOXLAB_WITH_VIEWER=ON >/dev/null
  case "$mode" in
    --test|--test-all) cmake --build "$build" -j "$jobs" ;;
    *) cmake --build "$build" -j "$jobs" --target voxlab ;;
  esac
fi

export LP_NUM_THREADS="${LP_NUM_THREADS:-$jobs}"

# 3. The main job, or the tests.
case "$mode" in
  run)
    if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
      exec "$build/bin/voxlab" view
    fi
    mkdir -p "$build/out"
    "$build/bin/voxlab" render "$root/datasets/scenes/default.json" --out "$build/out/default.png"
    ;;
  --grader)
    "$build/bin/voxlab" list >/dev/null && echo "setup: $build/bin/voxlab is ready to grade"
    ;;
  --test)
    cd "$build" && ctest --output-on-failure -j "$jobs" -LE heavy
    ;;
  --test-all)
    cd "$build" && ctest --output-on-failure -j "$jobs"
    ;;
  --web)
    if [ ! -x "$root/tools/setup_web.sh" ] || [ ! -d "$root/web" ]; then
      echo "setup: this tree has no browser build (web/): a student release uses the page its course hosts" >&2
      exit 1
    fi
    exec "$root/tools/setup_web.sh"
    ;;
esac
