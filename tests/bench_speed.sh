#!/usr/bin/env bash
# tests/bench_speed.sh: rastty against Mesa llvmpipe (OSMesa), side by side in one run.
#
#   tests/bench_speed.sh [--rounds N] [--frames N]
#
# Workloads (the speed issue's): the textured african_head, Gouraud and per-pixel Phong,
# nearest texture, back faces culled, camera (0,0,3), fov 40, clear + draw, at 160x96,
# 320x200 and 640x480; the shared bunny, sports car and lost_empire framed at 160x96; the
# demo scene's whole viewer frame as the viewer draws it (level of detail auto, the
# headlight; render + encode, `rastty bench`); OBJ load speed of the largest shared model.
# Then the ratios the speed issue's targets are about: Phong / Gouraud per size, and what
# every core gives over one at 640x480. rastty: `render --repeat N --stats` (median of N frames);
# Mesa: build/bench/glbench (ordinary OpenGL: RGBA8, GLSL; median of N frames after 10 of
# warm-up). Each pair runs --rounds times, alternating rastty and Mesa so that other load on
# the machine hits both alike; the table shows the median over rounds and the ratio
# rastty/Mesa, one thread each (LP_NUM_THREADS=0, --threads 1) and every core each.
# Numbers, never verdicts.
set -u
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
S=${RASTTY_SHARED:-../shared}/models
GL=build/bench/glbench
rounds=3 frames=100
while [ $# -gt 0 ]; do
    case $1 in
    --rounds) rounds=$2; shift ;;
    --frames) frames=$2; shift ;;
    *) echo "usage: tests/bench_speed.sh [--rounds N] [--frames N]" >&2; exit 2 ;;
    esac
    shift
done
if [ ! -x "$GL" ]; then
    echo "-- speed: skipped ($GL missing: make oracle-build needs OSMesa)"
    exit 0
fi
if [ ! -d "$S/african_head" ]; then
    echo "-- speed: skipped (no shared models at $S)"
    exit 0
fi
cores=$(nproc)
med() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
ms_of() { sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p'; }
# row LABEL THREADS(1|all) RASTTY_ARGS... -- MESA_ARGS...
row() {
    local label=$1 threads=$2; shift 2
    local ra=() ma=() seen=0
    for a in "$@"; do
        if [ "$a" = -- ]; then seen=1; continue; fi
        if [ $seen = 0 ]; then ra+=("$a"); else ma+=("$a"); fi
    done
    local rt=() mt=() r m
    local rthreads=$cores lp=()
    [ "$threads" = 1 ] && rthreads=1 && lp=(LP_NUM_THREADS=0)
    for _ in $(seq "$rounds"); do
        r=$("$BIN" render "${ra[@]}" --threads "$rthreads" --repeat "$frames" --stats \
            --out build/bench/speed.ppm 2>&1 | ms_of)
        m=$(env "${lp[@]}" "$GL" "${ma[@]}" --frames "$frames" | ms_of)
        rt+=("$r") mt+=("$m")
    done
    r=$(printf '%s\n' "${rt[@]}" | med) m=$(printf '%s\n' "${mt[@]}" | med)
    printf '  %-34s %-7s %9.3f %9.3f %7.2fx\n' "$label" "$threads" "$r" "$m" \
        "$(awk -v a="$r" -v b="$m" 'BEGIN { print a / b }')"
    results+=("$label|$threads|$r|$m")
}
results=()
# the median of a row already printed: field 3 (rastty) or 4 (mesa) of LABEL THREADS
got() {
    local e
    for e in "${results[@]}"; do
        IFS='|' read -r l t r m <<<"$e"
        if [ "$l" = "$1" ] && [ "$t" = "$2" ]; then
            [ "$3" = 3 ] && echo "$r" || echo "$m"
            return
        fi
    done
}
mkdir -p build/bench
echo "-- speed: rastty against Mesa llvmpipe, median ms/frame over $rounds alternating rounds of $frames frames ($cores cores)"
printf '  %-34s %-7s %9s %9s %8s\n' workload threads rastty mesa ratio
H="$S/african_head/african_head.obj"
T="$S/african_head/african_head_diffuse.tga"
for shade in gouraud phong; do
    for size in 160x96 320x200 640x480; do
        for th in 1 all; do
            row "head $shade $size" $th "$H" --texture "$T" --shade $shade --filter nearest \
                --cull back --fov 40 --size $size -- \
                "$H" --texture "$T" --shade $shade --cull back --fov 40 --size $size
        done
    done
done
for m in bunny/bunny.obj sports_car/sportsCar.obj lost_empire/lost_empire.obj; do
    [ -f "$S/$m" ] || continue
    cam=$("$BIN" render "$S/$m" --frame --size 160x96 --stats --out build/bench/speed.ppm 2>&1 |
          sed -n 's/^camera: //p')
    read -r -a camv <<<"$cam"
    for th in 1 all; do
        row "$(basename "$m" .obj) gouraud 160x96" $th "$S/$m" --frame --size 160x96 \
            --shade gouraud --cull back -- "$S/$m" "${camv[@]}" --size 160x96 --cull back
    done
done
echo "-- the demo scene's whole viewer frame, 160x48 cells, as the viewer draws it (--lod auto,"
echo "   --light camera; render + diff truecolor encode and nothing else between frames; median"
echo "   of 120 frames orbiting 2 deg, then the median over $rounds runs)"
for th in 1 $cores; do
    rs=() es=() fs=()
    for _ in $(seq "$rounds"); do
        read -r f r e < <("$BIN" bench assets/demo.rsc --cols 160 --rows 48 --frames 120 --orbit 2 \
            --threads $th --lod auto --light camera |
            awk '/viewer frame/ { f = $0; sub(/.*median /, "", f); split(f, w, " ")
                                  print w[1], w[4], w[7] + 0 }')
        fs+=("$f") rs+=("$r") es+=("$e")
    done
    printf '  threads %-3s render %.3f ms + encode %.3f ms: frame %.3f ms\n' $th \
        "$(printf '%s\n' "${rs[@]}" | med)" "$(printf '%s\n' "${es[@]}" | med)" \
        "$(printf '%s\n' "${fs[@]}" | med)"
done
echo "-- OBJ load (parse + mesh build), largest shared model"
big=$(ls -S "$S"/*/*.obj 2>/dev/null | head -n 1)
if [ -n "$big" ]; then
    bytes=$(stat -c %s "$big")
    loads=()
    for _ in $(seq "$rounds"); do
        loads+=("$("$BIN" render "$big" --frame --stats --out build/bench/speed.ppm 2>&1 |
                  sed -n 's/.*load_ms=\([0-9.]*\).*/\1/p')")
    done
    l=$(printf '%s\n' "${loads[@]}" | med)
    printf '  %s: %.1f MB in %.1f ms = %.0f MB/s\n' "$(basename "$big")" \
        "$(awk -v b="$bytes" 'BEGIN { print b / 1e6 }')" "$l" \
        "$(awk -v b="$bytes" -v l="$l" 'BEGIN { print b / 1e6 / (l / 1e3) }')"
fi
echo "-- the targets' ratios, from the medians above"
for size in 160x96 320x200 640x480; do
    g=$(got "head gouraud $size" 1 3) p=$(got "head phong $size" 1 3)
    printf '  Phong / Gouraud, one thread, %-8s %.2fx\n' "$size" "$(awk -v a="$p" -v b="$g" 'BEGIN { print a / b }')"
done
for shade in gouraud phong; do
    r1=$(got "head $shade 640x480" 1 3) ra=$(got "head $shade 640x480" all 3)
    m1=$(got "head $shade 640x480" 1 4) ma=$(got "head $shade 640x480" all 4)
    printf '  %s cores over one, head %-8s 640x480: rastty %.2fx, Mesa %.2fx\n' "$cores" "$shade" \
        "$(awk -v a="$r1" -v b="$ra" 'BEGIN { print a / b }')" "$(awk -v a="$m1" -v b="$ma" 'BEGIN { print a / b }')"
done
