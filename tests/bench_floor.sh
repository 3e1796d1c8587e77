#!/usr/bin/env bash
# tests/bench_floor.sh: where the single-thread speed workload's time goes (part of `make
# bench`; numbers, never verdicts). The textured african_head, Gouraud, nearest texture,
# back-face culling, fov 40, one thread (tests/bench_speed.sh's workload), drawn in
# alternating rounds by:
#   ./rastty                      the build everyone runs
#   build/floor-texels/rastty     every texel fetch reads one of the first 16 texels: the
#                                 frame without the texture's cache misses (texture.h)
#   build/floor-setup2/rastty     interpolation setup done twice: the frame plus one more
#                                 setup's cost (kernel_span.h)
#   Mesa llvmpipe (glbench)       one thread (LP_NUM_THREADS=0), the same scene
# and then, from the times: what the texture's misses and the setup cost a frame, the issue's
# target (0.25x Mesa at 160x96, 0.40x at 640x480), and the frame with both taken out.
#   tests/bench_floor.sh [--rounds N] [--frames N]
# Needs `make floor-build oracle-build` and the shared models; skips without them.
set -u
cd "$(dirname "$0")/.." || exit 2
S=${RASTTY_SHARED:-../shared}/models
GL=build/bench/glbench
rounds=11 frames=300
while [ $# -gt 0 ]; do
    case $1 in
    --rounds) rounds=$2; shift ;;
    --frames) frames=$2; shift ;;
    *) echo "usage: tests/bench_floor.sh [--rounds N] [--frames N]" >&2; exit 2 ;;
    esac
    shift
done
bins=(./rastty build/floor-texels/rastty build/floor-setup2/rastty)
for b in "${bins[@]}" "$GL"; do
    if [ ! -x "$b" ]; then
        echo "-- floor: skipped ($b missing: make floor-build oracle-build)"
        exit 0
    fi
done
if [ ! -d "$S/african_head" ]; then
    echo "-- floor: skipped (no shared models at $S)"
    exit 0
fi
H="$S/african_head/african_head.obj"
T="$S/african_head/african_head_diffuse.tga"
# the least of the rounds' medians: this machine's noise only ever adds time, and a burst can
# outlast several rounds (a median over rounds moved Mesa's 640x480 from 1.99 to 2.54 ms)
least() { sort -g | head -1; }
ms_of() { sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p'; }
mkdir -p build/bench
echo "-- where the time goes: head gouraud, one thread, ms/frame: the least of $rounds alternating"
echo "   rounds' medians of $frames frames (build/floor-*: texture.h, kernel_span.h; tests/bench_floor.sh)"
printf '  %-8s %8s %10s %10s %8s %9s %9s %9s %11s\n' size rastty no-misses setup-x2 mesa \
    misses setup target "rastty-both"
for size in 160x96 640x480; do
    args=("$H" --texture "$T" --shade gouraud --filter nearest --cull back --fov 40 --size "$size"
          --threads 1 --repeat "$frames" --stats --out build/bench/floor.ppm)
    t0=() t1=() t2=() tm=()
    for _ in $(seq "$rounds"); do
        t0+=("$("${bins[0]}" render "${args[@]}" 2>&1 | ms_of)")
        t1+=("$("${bins[1]}" render "${args[@]}" 2>&1 | ms_of)")
        t2+=("$("${bins[2]}" render "${args[@]}" 2>&1 | ms_of)")
        tm+=("$(LP_NUM_THREADS=0 "$GL" "$H" --texture "$T" --shade gouraud --cull back --fov 40 \
                --size "$size" --frames "$frames" | ms_of)")
    done
    a=$(printf '%s\n' "${t0[@]}" | least) b=$(printf '%s\n' "${t1[@]}" | least)
    c=$(printf '%s\n' "${t2[@]}" | least) m=$(printf '%s\n' "${tm[@]}" | least)
    k=0.40
    [ "$size" = 160x96 ] && k=0.25
    awk -v size="$size" -v a="$a" -v b="$b" -v c="$c" -v m="$m" -v k="$k" 'BEGIN {
        miss = a - b; setup = c - a; target = k * m; both = a - miss - setup
        printf "  %-8s %8.3f %10.3f %10.3f %8.3f %9.3f %9.3f %9.3f %11.3f\n", size, a, b, c, m,
            miss, setup, target, both }'
done
echo "   misses = rastty - no-misses; setup = setup-x2 - rastty; target = the issue's ratio x mesa;"
echo "   rastty-both = rastty with the misses and the setup both taken out"
