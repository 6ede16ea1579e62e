#!/usr/bin/env bash
# voxlab in the browser: builds the WebAssembly viewer and its page into
# build-web/site (called by `tools/setup.sh --web`; see docs/web.md).
#
#   1. installs Debian's emscripten (and chromium, for the browser test) if
#      they are missing;
#   2. fetches Debian's source packages of Dear ImGui and zlib into
#      build-web/third_party with apt's own client, through a private list
#      folder (nothing in /etc/apt changes), since emscripten's "ports" would
#      download from the internet at build time;
#   3. generates the pristine starter code (tools/make_assignments.py --out)
#      and installs markdown-it (npm ci, web/page's lock file), then
#      configures web/ with emcmake and builds it.
#
#   tools/setup_web.sh --test   the same, then the browser test
#       (web/test/browser_test.mjs: headless chromium, screenshots and
#       figures in build-web/browser-test/).
#
# Environment: VOXLAB_WEB_BUILD_DIR (default: build-web), VOXLAB_JOBS, and
# VOXLAB_WEB_TREE: the tree whose stages, datasets and expected images the
# page holds. By default this repository, whose reference/ (the model
# answers) goes into the page too, so the test can check it; for students,
# a student release (tools/make_student_release.sh DIR), which has no
# reference/ and brings its own expected/.
set -euo pipefail
mode="${1:-build}"
case "$mode" in
  build|--test) ;;
  *) echo "setup_web.sh: unknown argument '$mode' (expected --test or nothing)" >&2; exit 2 ;;
esac

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${VOXLAB_WEB_BUILD_DIR:-$root/build-web}"
jobs="${VOXLAB_JOBS:-$(nproc 2>/dev/null || echo 2)}"
tree=$(cd "${VOXLAB_WEB_TREE:-$root}" && pwd)
if [ "$mode" = --test ] && [ ! -d "$tree/reference" ]; then
  echo "setup_web.sh: --test checks the reference's self-check, which $tree (a student release?) does not hold" >&2
  exit 2
fi

packages=(emscripten chromium glslang-tools fonts-dejavu-core libglm-dev libstb-dev nlohmann-json3-dev)
command -v npm >/dev/null || packages+=(npm)  # markdown-it for the page, playwright-core for its test
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup-web: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# emscripten's JavaScript tools require acorn, which Debian installs under
# /usr/share/nodejs; a Node.js from elsewhere (nodesource) does not look there.
export NODE_PATH="/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}"

# 2. Sources of Dear ImGui and zlib, from the archive this machine already uses.
third="$build/third_party"
if ! ls -d "$third"/imgui-* "$third"/zlib-* >/dev/null 2>&1; then
  apt_dir="$build/apt"
  mkdir -p "$apt_dir/lists/partial" "$third"
  mirror=$(sed -n 's/^URIs: *//p; s/^deb  *\(http[^ ]*\).*/\1/p' /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null \
           | grep -v security | head -n 1 || true)
  suite=$(. /etc/os-release && echo "${VERSION_CODENAME:-bookworm}")
  echo "deb-src ${mirror:-http://deb.debian.org/debian} $suite main" > "$apt_dir/sources.list"
  apt_opts=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o "Dir::Etc::SourceParts=/dev/null"
            -o "Dir::State::Lists=$apt_dir/lists")
  apt-get "${apt_opts[@]}" update -qq
  (cd "$third" && apt-get "${apt_opts[@]}" source --download-only -qq imgui zlib 2>/dev/null \
     && for t in *.orig.tar.*; do tar xf "$t"; done)
  ls -d "$third"/imgui-* "$third"/zlib-* >/dev/null || { echo "setup-web: could not fetch the imgui and zlib sources" >&2; exit 1; }
fi

# Links to Debian's header-only libraries, so that emscripten sees them
# without the host's /usr/include.
mkdir -p "$build/include"
for h in glm nlohmann stb; do ln -sfn "/usr/include/$h" "$build/include/$h"; done

# The self-check's expected images: every stage's scenes rendered by the
# reference with the native build (tools/setup.sh builds it first).
if [ -d "$tree/expected" ]; then
  echo "setup-web: the expected images of $tree/expected"
elif [ ! -d "$build/expected" ] || [ -n "$(find "$root/reference" "$root/shaders" "$root/build/bin/voxlab" -newer "$build/expected" 2>/dev/null | head -n 1)" ]; then
  [ -x "$root/build/bin/voxlab" ] || { echo "setup-web: no native build at $root/build (run tools/setup.sh first)" >&2; exit 1; }
  echo "setup-web: rendering the expected images with the reference"
  rm -rf "$build/expected.tmp"
  LP_NUM_THREADS="${LP_NUM_THREADS:-$jobs}" "$root/build/bin/voxlab" grade --render-expected "$build/expected.tmp" --quiet >/dev/null
  rm -rf "$build/expected" && mv "$build/expected.tmp" "$build/expected" && touch "$build/expected"
fi

# The starter code the page offers: the pristine one, generated from
# reference/ (tools/make_assignments.py --out), never assignments/ as it is
# on this machine, which may hold someone's half-done work. A release has no
# generator: its assignments/ go in as they are, and this says so.
starter="$build/starter"
if [ -d "$tree/reference" ] && [ -f "$tree/tools/make_assignments.py" ]; then
  rm -rf "$starter.tmp" && python3 "$tree/tools/make_assignments.py" --out "$starter.tmp" >/dev/null
  rm -rf "$starter" && mv "$starter.tmp" "$starter"
  if ! python3 "$tree/tools/make_assignments.py" --check >/dev/null 2>"$build/starter-drift.txt"; then
    echo "setup-web: $tree/assignments differs from the starter code ($(grep -c ': ' "$build/starter-drift.txt") files," \
         "e.g. $(head -n 1 "$build/starter-drift.txt" | cut -d: -f1)); the page packs the pristine starter from reference/"
  fi
  echo "setup-web: packing the pristine starter code (tools/make_assignments.py --out $starter)"
else
  starter="$tree/assignments"
  echo "setup-web: packing $starter as it is (no reference/ to generate the pristine starter from)"
fi

# The handouts' Markdown renderer (markdown-it), pinned by web/page/package-lock.json.
[ -f "$root/web/page/node_modules/markdown-it/package.json" ] || npm ci --prefix "$root/web/page" --no-audit --no-fund --silent

# 3. Configure and build.
emcmake cmake -S "$root/web" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVOXLAB_WEB_TREE="$tree" \
  -DVOXLAB_WEB_STARTER="$starter" >/dev/null
cmake --build "$build" -j "$jobs"
echo "setup-web: the page is in $build/site: serve it with"
echo "  (cd $build/site && /usr/bin/python3 -m http.server 8000)   and open http://localhost:8000/"
[ "$mode" = --test ] || exit 0

# 4. The browser test: playwright-core (npm, pinned by web/test/package-lock.json)
#    drives Debian's chromium; it downloads no browser of its own.
command -v npm >/dev/null || { echo "setup-web: the browser test needs Node.js's npm" >&2; exit 1; }
[ -d "$root/web/test/node_modules/playwright-core" ] || npm ci --prefix "$root/web/test" --no-audit --no-fund --silent
# The native `voxlab check` of the same stage, whose verdicts the page's
# self-check must repeat.
for side in reference assignments; do
  submission="$root/reference"
  [ "$side" = assignments ] && submission="$starter"
  LP_NUM_THREADS="${LP_NUM_THREADS:-$jobs}" "$root/build/bin/voxlab" check --stage mip --submission "$submission" \
    --out "$build/native-check-$side" >/dev/null || true
done
node "$root/web/test/browser_test.mjs" "$build/site" "$build/browser-test" \
  "$build/native-check-reference/report.json" "$build/native-check-assignments/report.json"
