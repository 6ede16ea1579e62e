#!/usr/bin/env bash
# Installs bench/gpu_kit.sh's kit on a GPU machine (as root; run from the
# repository root, with BUILD/gpu-kit carried there):
#
#   bench/gpu_machine_setup.sh [BUILD]
#
# - the kit's libraries go to /usr/local/lib (only those the machine lacks),
#   where the grader's sandbox may read them (LD_LIBRARY_PATH does not reach
#   a sandboxed worker), then ldconfig;
# - glvnd's packages are unpacked into / when the machine has no libEGL.so.1;
# - GLM's headers go to /usr/include/glm when missing (C++ stages);
# - the tree is linked at the path the binary was built in, when it sits
#   elsewhere (a C++ stage's build names that path's framework/include/MODULE).
# Then it prints the EGL device voxlab finds.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${1:-$root/build}"
kit="$build/gpu-kit"
[ -d "$kit" ] || { echo "gpu_machine_setup.sh: no kit at $kit (bench/gpu_kit.sh makes it)" >&2; exit 1; }
[ -d "$kit/lib" ] || tar -C "$kit" -xJf "$kit/lib.tar.xz"
for lib in "$kit"/lib/*; do
  name=$(basename "$lib")
  if [ "$name" = libOSMesa.so.8 ] || ! ldconfig -p | grep -q "/$name\$"; then cp "$lib" /usr/local/lib/; fi
done
if ! ldconfig -p | grep -q "libEGL.so.1 "; then
  for deb in "$kit"/debs/*.deb; do dpkg -x "$deb" /; done
fi
[ -d /usr/include/glm ] || cp -r "$kit/include/glm" /usr/include/glm
ldconfig
# The build folder the binary names (its prebuilt stage exports), whose
# parent is the source tree it was configured from.
built_build=$(strings "$build/bin/voxlab" | grep -o '/[^ ]*/framework/CMakeFiles/voxlab_stage_exports.dir' | head -n 1 |
              sed 's|/framework/CMakeFiles/voxlab_stage_exports.dir$||')
built=${VOXLAB_BUILT_AT:-$(dirname "${built_build:-/nonexistent/x}")}
if [ -n "$built" ] && [ "$built" != "$root" ] && [ ! -e "$built" ]; then
  mkdir -p "$(dirname "$built")"
  ln -s "$root" "$built"
fi
VOXLAB_GL=egl "$build/bin/voxlab" render --dataset phantom:marschner-lobb:32 --size 32x32 --gl egl --verbose \
  --out /tmp/voxlab-egl-check.png 2>&1 | grep -m1 -i "egl" || true
