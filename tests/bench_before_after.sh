#!/usr/bin/env bash
# tests/bench_before_after.sh OLD [NEW]: did a change make rastty slower? Two rastty binaries
# (OLD, e.g. a build of the commit before the change; NEW by default ./rastty) run the same
# workloads alternately, ROUNDS times each (default 7), so that other load on the machine
# hits both alike; prints the median ms/frame of each and NEW/OLD. Workloads: the textured
# african_head (Gouraud and Phong, 160x96 and 640x480, one thread; Phong 640x480 on two),
# the shared bunny, sports car and lost_empire framed at 160x96, and the demo's whole viewer
# frame (render + encode, `rastty bench`). Needs ../shared/models. Numbers, never verdicts.
#   git worktree add /tmp/old COMMIT && make -C /tmp/old && tests/bench_before_after.sh /tmp/old/rastty
set -u
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: tests/bench_before_after.sh OLD [NEW]" >&2; exit 2; }
OLD=$1 NEW=${2:-./rastty} ROUNDS=${ROUNDS:-7}
S=${RASTTY_SHARED:-../shared}/models
if [ ! -d "$S/african_head" ]; then
    echo "-- before/after: skipped (no shared models at $S)"
    exit 0
fi
H=$S/african_head/african_head.obj T=$S/african_head/african_head_diffuse.tga
out=$(mktemp /tmp/rastty-ba.XXXXXX.ppm)
trap 'rm -f "$out"' EXIT
med() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
ms_of() { sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p'; }
line() { # label old-times new-times
    local a b; a=$(printf '%s\n' $2 | med) b=$(printf '%s\n' $3 | med)
    printf '  %-36s %9.3f %9.3f %7.2fx\n' "$1" "$a" "$b" "$(awk -v a="$a" -v b="$b" 'BEGIN { print b / a }')"
}
row() { # label frames render-args...
    local label=$1 fr=$2 o="" n=""; shift 2
    for _ in $(seq "$ROUNDS"); do
        o+=" $("$OLD" render "$@" --repeat "$fr" --stats --out "$out" 2>&1 | ms_of)"
        n+=" $("$NEW" render "$@" --repeat "$fr" --stats --out "$out" 2>&1 | ms_of)"
    done
    line "$label" "$o" "$n"
}
demo() { # binary: the viewer frame's median ms
    "$1" bench assets/demo.rsc --cols 160 --rows 48 --frames 120 --orbit 2 --threads 1 \
        --lod auto --light camera 2>&1 |
        awk '/viewer frame/ { f = $0; sub(/.*median /, "", f); split(f, w, " "); print w[1] }'
}
echo "-- before/after: median ms/frame, $ROUNDS alternating rounds ($OLD, then $NEW)"
printf '  %-36s %9s %9s %8s\n' "workload (one thread unless said)" before after after/before
for shade in gouraud phong; do
    for size in 160x96 640x480; do
        row "head $shade $size" 100 "$H" --texture "$T" --shade $shade --filter nearest \
            --cull back --fov 40 --size $size --threads 1
    done
done
row "head phong 640x480, 2 threads" 100 "$H" --texture "$T" --shade phong --filter nearest \
    --cull back --fov 40 --size 640x480 --threads 2
for m in bunny/bunny.obj:30 sports_car/sportsCar.obj:10 lost_empire/lost_empire.obj:10; do
    [ -f "$S/${m%:*}" ] || continue
    row "$(basename "${m%:*}" .obj) gouraud 160x96" "${m#*:}" "$S/${m%:*}" --frame \
        --size 160x96 --shade gouraud --cull back --threads 1
done
o="" n=""
for _ in $(seq "$ROUNDS"); do o+=" $(demo "$OLD")" n+=" $(demo "$NEW")"; done
line "demo viewer frame (render + encode)" "$o" "$n"
