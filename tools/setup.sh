#!/usr/bin/env bash
# voxlab set-up, from a fresh Debian 12 machine to a running program.
#
#   tools/setup.sh          install what is missing, build, and run the main
#                           job: the viewer on the default scene when a
#                           display is available, else a headless render of
#                           the default scene to a PNG whose path it prints.
#   tools/setup.sh --test   the same set-up, then the whole test suite
#                           (tests labelled "heavy" too with --test-all).
#   tools/setup.sh --grader only what grading needs (an autograder image:
#                           tools/gradescope/): the packages for headless
#                           rendering and the voxlab program, no viewer and
#                           no tests. Works on Debian 12 and Ubuntu 22.04,
#                           whose package names are the same.
#
# Environment: VOXLAB_BUILD_DIR (default: build), VOXLAB_JOBS (default: nproc).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${VOXLAB_BUILD_DIR:-$root/build}"
jobs="${VOXLAB_JOBS:-$(nproc 2>/dev/null || echo 2)}"
mode="${1:-run}"
case "$mode" in
  run|--test|--test-all|--grader) ;;
  -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
  *) echo "setup.sh: unknown argument '$mode' (expected --test, --test-all, --grader or nothing)" >&2; exit 2 ;;
esac

# 1. System packages (Debian 12 names). Only the missing ones are installed.
packages=(cmake make g++ pkg-config python3 libglm-dev libstb-dev libosmesa6-dev libegl-dev zlib1g-dev
          nlohmann-json3-dev khronos-api)
[ "$mode" = --grader ] || packages+=(libglfw3-dev libimgui-dev libgtest-dev xvfb xauth)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# 2. Configure and build.
if [ "$mode" = --grader ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVOXLAB_BUILD_TESTS=OFF -DVOXLAB_WITH_VIEWER=OFF >/dev/null
  cmake --build "$build" -j "$jobs" --target voxlab
else
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVOXLAB_BUILD_TESTS=ON -DVOXLAB_WITH_VIEWER=ON >/dev/null
  cmake --build "$build" -j "$jobs"
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
esac
