#!/bin/sh
# Regenerates golden images on purpose: tools/update_golden.sh NAME... or --all.
# Each NAME is an entry of tests/golden/golden.json; its scene
# tests/golden/scenes/NAME.json is rendered with build/bin/voxlab into
# tests/golden/images/NAME.png. Review the new images (git diff shows which
# changed) before committing them. The golden test itself never writes here.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
voxlab=${VOXLAB_BINARY:-$root/build/bin/voxlab}
golden=$root/tests/golden
if [ $# -eq 0 ]; then
    echo "usage: tools/update_golden.sh NAME... | --all   (names: tests/golden/golden.json)" >&2
    exit 2
fi
[ -x "$voxlab" ] || { echo "update_golden: $voxlab not found: build first (tools/setup.sh --test)" >&2; exit 1; }
names=$(python3 -c 'import json,sys; print(" ".join(e["name"] for e in json.load(open(sys.argv[1]))["images"]))' "$golden/golden.json")
if [ "$1" = "--all" ]; then set -- $names; fi
mkdir -p "$golden/images"
for name in "$@"; do
    case " $names " in *" $name "*) ;; *) echo "update_golden: '$name' is not in tests/golden/golden.json" >&2; exit 1 ;; esac
    LP_NUM_THREADS=${LP_NUM_THREADS:-2} VOXLAB_GL=osmesa "$voxlab" render "$golden/scenes/$name.json" \
        --out "$golden/images/$name.png" >/dev/null
    echo "updated tests/golden/images/$name.png"
done
