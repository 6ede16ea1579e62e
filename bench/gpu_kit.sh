#!/usr/bin/env bash
# Packs what a Debian-built voxlab needs on a GPU machine that has NVIDIA's
# (or another vendor's) driver but no Debian packages and no network
# (../shared/notes/gpu-device.md has the facts behind each step):
#
#   bench/gpu_kit.sh [BUILD]          writes BUILD/gpu-kit/ (default build/)
#
#   lib.tar.xz: lib/ and include/, packed:
#   lib/      the shared libraries `ldd voxlab` names, less the C library,
#             libstdc++ and libgcc, and less OSMesa and what only it needs
#             (LLVM and its kin): a GPU machine renders through EGL
#   lib/libOSMesa.so.8   a stand-in whose functions fail (bench/osmesa_standin.c)
#   debs/     glvnd's libEGL and libGLdispatch, as Debian packages, for a
#             machine whose EGL comes only with the vendor's library
#   include/glm          GLM's headers, for compiling C++ stages there
# On the GPU machine, bench/gpu_machine_setup.sh installs it.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${1:-$root/build}"
kit="$build/gpu-kit"
rm -rf "$kit"
mkdir -p "$kit/lib" "$kit/debs" "$kit/include"

# Every library voxlab's direct dependencies need, transitively, except
# OSMesa's own tree.
skip=" libc.so.6 libm.so.6 libstdc++.so.6 libgcc_s.so.1 libdl.so.2 libpthread.so.0 libOSMesa.so.8 "
declare -A wanted=()
for direct in $(readelf -d "$build/bin/voxlab" | sed -n 's/.*Shared library: \[\(.*\)\]/\1/p'); do
  [ "$direct" = libOSMesa.so.8 ] && continue
  path=$(ldd "$build/bin/voxlab" | awk -v l="$direct" '$1 == l {print $3}')
  [ -n "$path" ] || continue
  wanted[$direct]=$path
  while read -r name arrow dep rest; do
    [ "$arrow" = "=>" ] && [ -n "$dep" ] && wanted[$name]=$dep
  done < <(ldd "$path")
done
for lib in "${!wanted[@]}"; do
  [[ "$skip" == *" $lib "* ]] && continue
  cp -L "${wanted[$lib]}" "$kit/lib/$lib"
done
cc -shared -fPIC -O2 -Wl,-soname,libOSMesa.so.8 -o "$kit/lib/libOSMesa.so.8" "$root/bench/osmesa_standin.c"
(cd "$kit/debs" && apt-get download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null 2>&1) ||
  echo "gpu_kit.sh: apt-get download failed: no glvnd packages in the kit" >&2
cp -r /usr/include/glm "$kit/include/glm"
# Packed: ICU's data alone is 31 MB, a third of it packed.
tar -C "$kit" -cJf "$kit/lib.tar.xz" lib include
rm -rf "$kit/lib" "$kit/include"
du -sh "$kit" | awk '{print "gpu_kit.sh: " $2 " (" $1 ")"}'
