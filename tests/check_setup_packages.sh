#!/usr/bin/env bash
# Checks tools/setup.sh's package step on a fake Debian 12 and a fake Ubuntu
# 22.04 (Gradescope's base image) without installing anything: an os-release
# file of each (VOXLAB_OS_RELEASE) and stand-ins for dpkg-query, apt-cache,
# apt-get, sudo and cmake on PATH, which report what the test says and log
# their calls. It checks the package list chosen for each system and mode,
# the apt-get calls, and that a package apt cannot find stops the set-up,
# before installing or building, with one line naming it.
# Usage: check_setup_packages.sh PROJECT_SOURCE_DIR
set -u

src_dir=${1:?usage: check_setup_packages.sh PROJECT_SOURCE_DIR}
setup="$src_dir/tools/setup.sh"
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

printf 'PRETTY_NAME="Debian GNU/Linux 12 (bookworm)"\nNAME="Debian GNU/Linux"\nVERSION_ID="12"\nID=debian\n' >"$tmp/debian12"
printf 'PRETTY_NAME="Ubuntu 22.04.4 LTS"\nNAME="Ubuntu"\nVERSION_ID="22.04"\nID=ubuntu\nID_LIKE=debian\n' >"$tmp/ubuntu2204"
printf 'NAME="Fedora Linux"\nVERSION_ID=39\nID=fedora\n' >"$tmp/fedora39"

# Stand-ins. FAKE_INSTALLED: packages dpkg reports installed; FAKE_UNAVAILABLE:
# packages apt has no candidate for (as when Ubuntu's universe is off).
mkdir -p "$tmp/bin" "$tmp/build/bin"
cat >"$tmp/bin/dpkg-query" <<'EOF'
#!/usr/bin/env bash
p=${!#}
[[ " ${FAKE_INSTALLED:-} " == *" $p "* ]] || exit 1
printf 'install ok installed'
EOF
cat >"$tmp/bin/apt-cache" <<'EOF'
#!/usr/bin/env bash
[ "$1" = policy ] || exit 100
[[ " ${FAKE_UNAVAILABLE:-} " == *" $2 "* ]] && exit 0
printf '%s:\n  Installed: (none)\n  Candidate: 1.0-1\n' "$2"
EOF
cat >"$tmp/bin/apt-get" <<'EOF'
#!/usr/bin/env bash
echo "apt-get $*" >>"$FAKE_LOG"
EOF
cat >"$tmp/bin/sudo" <<'EOF'
#!/usr/bin/env bash
exec "$@"
EOF
cat >"$tmp/bin/cmake" <<'EOF'
#!/usr/bin/env bash
echo "cmake $*" >>"$FAKE_LOG"
EOF
cat >"$tmp/bin/ctest" <<'EOF'
#!/usr/bin/env bash
echo "ctest $*" >>"$FAKE_LOG"
EOF
printf '#!/bin/sh\nexit 0\n' >"$tmp/build/bin/voxlab"
chmod +x "$tmp/bin/"* "$tmp/build/bin/voxlab"

grader="cmake make g++ pkg-config python3 libglm-dev libstb-dev libosmesa6-dev libegl-dev zlib1g-dev nlohmann-json3-dev khronos-api libgdcm-dev libseccomp-dev libarchive-dev"
full="$grader libglfw3-dev libimgui-dev libgtest-dev xvfb xauth fonts-dejavu-core python3-pydicom python3-numpy glslang-tools dpkg-dev"

# run OS_RELEASE ARGS...: runs setup.sh with the stand-ins; sets out, err, rc, log.
run() {
  local os=$1
  shift
  : >"$tmp/log"
  out=$(PATH="$tmp/bin:$PATH" FAKE_LOG="$tmp/log" VOXLAB_OS_RELEASE="$tmp/$os" VOXLAB_BUILD_DIR="$tmp/build" \
        VOXLAB_JOBS=1 bash "$setup" "$@" 2>"$tmp/err")
  rc=$?
  err=$(cat "$tmp/err")
  log=$(cat "$tmp/log")
}
expect() {  # expect WHAT WANT GOT
  [ "$2" = "$3" ] || fail "$1: expected [$2], got [$3]"
}

# The package list each system and mode chooses (dry run: nothing runs).
for os in debian12 ubuntu2204; do
  name=$([ $os = debian12 ] && echo "debian 12" || echo "ubuntu 22.04")
  for mode in --grader "" --test; do
    want=$([ "$mode" = --grader ] && echo "$grader" || echo "$full")
    VOXLAB_SETUP_DRY_RUN=1 FAKE_INSTALLED="cmake make" run $os $mode
    expect "$os ${mode:-run}: exit status" 0 "$rc"
    expect "$os ${mode:-run}: packages" "setup: $name: $want" "$(sed -n 1p <<<"$out")"
    expect "$os ${mode:-run}: missing" "setup: missing: ${want#cmake make }" "$(sed -n 2p <<<"$out")"
    expect "$os ${mode:-run}: stderr" "" "$err"
    expect "$os ${mode:-run}: calls" "" "$log"
  done
done

# Ubuntu 22.04, grader image, everything available: one update, one install
# of exactly the missing packages, then the grader build.
FAKE_INSTALLED="cmake make g++ python3" run ubuntu2204 --grader
expect "ubuntu install: exit status" 0 "$rc"
expect "ubuntu install: apt-get calls" \
  "apt-get update -qq
apt-get install -y -qq --no-install-recommends pkg-config libglm-dev libstb-dev libosmesa6-dev libegl-dev zlib1g-dev nlohmann-json3-dev khronos-api libgdcm-dev libseccomp-dev libarchive-dev" \
  "$(grep '^apt-get' <<<"$log")"
grep -q -- "-DVOXLAB_WITH_VIEWER=OFF" <<<"$log" || fail "ubuntu install: no grader build configured: $log"
expect "ubuntu install: stderr" "" "$err"

# Ubuntu 22.04 without universe: stops after apt-get update, before any
# install or build, with one line naming what is missing.
FAKE_UNAVAILABLE="libstb-dev nlohmann-json3-dev khronos-api" run ubuntu2204 --grader
expect "ubuntu without universe: exit status" 1 "$rc"
expect "ubuntu without universe: message" \
  "setup: not available from apt on ubuntu 22.04: libstb-dev nlohmann-json3-dev khronos-api (on Ubuntu, enable the 'universe' component)" \
  "$err"
expect "ubuntu without universe: calls" "apt-get update -qq" "$log"

# The same check in a dry run, and on Debian (no universe hint there).
VOXLAB_SETUP_DRY_RUN=1 FAKE_UNAVAILABLE="libimgui-dev" run debian12
expect "debian dry run, one unavailable: exit status" 1 "$rc"
expect "debian dry run, one unavailable: message" "setup: not available from apt on debian 12: libimgui-dev" "$err"
expect "debian dry run, one unavailable: calls" "" "$log"

# Nothing missing: no apt-get at all, straight to the build.
FAKE_INSTALLED="$full" run debian12 --grader
expect "debian, all installed: exit status" 0 "$rc"
grep -q '^apt-get' <<<"$log" && fail "debian, all installed: apt-get was called: $log"
grep -q '^cmake' <<<"$log" || fail "debian, all installed: no build: $log"

# The main job builds what it runs, the voxlab program (whose target brings
# the stage host); --test builds everything, then runs the tests.
FAKE_INSTALLED="$full" DISPLAY= WAYLAND_DISPLAY= run debian12
expect "debian, main job: exit status" 0 "$rc"
expect "debian, main job: build" "cmake --build $tmp/build -j 1 --target voxlab" "$(grep -- '^cmake --build' <<<"$log")"
FAKE_INSTALLED="$full" run debian12 --test
expect "debian, --test: exit status" 0 "$rc"
expect "debian, --test: build" "cmake --build $tmp/build -j 1" "$(grep -- '^cmake --build' <<<"$log")"
grep -q '^ctest .*-LE heavy' <<<"$log" || fail "debian, --test: the tests did not run: $log"

# Another system: one line saying it is untested, the same names.
VOXLAB_SETUP_DRY_RUN=1 run fedora39 --grader
expect "fedora: exit status" 0 "$rc"
expect "fedora: warning" "setup: fedora 39 is untested (Debian 12 and Ubuntu 22.04 are); trying their package names" "$err"
expect "fedora: packages" "setup: fedora 39: $grader" "$(sed -n 1p <<<"$out")"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) of tools/setup.sh's package step failed"
  exit 1
fi
echo "tools/setup.sh chooses and checks its packages as expected on Debian 12 and Ubuntu 22.04"
