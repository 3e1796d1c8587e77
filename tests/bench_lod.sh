#!/usr/bin/env bash
# tests/bench_lod.sh: mesh level of detail — what `--lod auto:PX` costs and saves for each
# bound PX, and the fixed levels (--lod RATIO), on the dense shared models (sports car 300k
# triangles, lost_empire 225k, bunny 69k) at 160x96 and 640x480. This is where auto's
# default bound (LOD_DEFAULT_PX, render.h) comes from; `make bench` prints it.
#
#   tests/bench_lod.sh [--views N] [--repeat N] [--px "0.1 0.25 ..."] [--csv FILE]
#
# Each model is seen from N directions around it (the eye orbits at 20 degrees up, framed:
# `render --eye ... --frame`). Per view: the ideal image (`--ssaa 8 --filter bilinear`, LOD
# off); then each setting, rendered with `--repeat N --stats --threads 1` (median_ms) and
# compared with the ideal by build/oracle/compare. Per setting the table shows the median
# over views of ms/frame, the PSNR pooled over views (mean squared error), its loss against
# --lod off, and the triangles drawn (median over views). Then build/bench/reorder: whether
# meshoptimizer's vertex-cache and overdraw orders would pay (they do not: README). Numbers,
# never verdicts.
set -u
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
S=${RASTTY_SHARED:-../shared}/models
CMP=build/oracle/compare
D=build/bench/lod
views=6 repeat=9 pxs="0.05 0.1 0.15 0.2 0.25 0.35 0.5 1" ratios="0.5 0.25 0.125" csv=
while [ $# -gt 0 ]; do
    case $1 in
    --views) views=$2; shift ;;
    --repeat) repeat=$2; shift ;;
    --px) pxs=$2; shift ;;
    --csv) csv=$2; shift ;;
    *) echo "usage: tests/bench_lod.sh [--views N] [--repeat N] [--px LIST] [--csv FILE]" >&2
       exit 2 ;;
    esac
    shift
done
if [ ! -x "$CMP" ]; then
    echo "-- lod: skipped ($CMP missing: make oracle-build)"
    exit 0
fi
models=()
for m in sports_car/sportsCar.obj lost_empire/lost_empire.obj bunny/bunny.obj; do
    [ -f "$S/$m" ] && models+=("$S/$m")
done
if [ ${#models[@]} = 0 ]; then
    echo "-- lod: skipped (no shared models at $S)"
    exit 0
fi
mkdir -p "$D"
settings=(off)
for p in $pxs; do settings+=("auto:$p"); done
for r in $ratios; do settings+=("$r"); done
echo "-- level of detail: $views views, median ms of $repeat frames (one thread), PSNR against the ideal pooled over the views"
printf '  %-12s %-8s %-10s %9s %8s %8s %9s\n' model size lod ms PSNR_dB loss_dB triangles
[ -n "$csv" ] && echo "model,size,lod,ms,psnr_db,loss_db,tris" > "$csv"
med() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
for m in "${models[@]}"; do
    name=$(basename "$m" .obj)
    for size in 160x96 640x480; do
        declare -A ms=() mse=() tris=()
        for v in $(seq 0 $((views - 1))); do
            eye=$(awk -v v="$v" -v n="$views" 'BEGIN { a = 6.2831853 * v / n; printf "%.6f,0.364,%.6f", sin(a), cos(a) }')
            cam=(--eye "$eye" --frame --size "$size")
            ideal=$D/$name.$size.$v.ideal
            "$BIN" render "$m" "${cam[@]}" --ssaa 8 --filter bilinear --out "$ideal.ppm" \
                --depth-out "$ideal.pfm" 2>/dev/null || { echo "  $name: render failed"; continue 2; }
            for s in "${settings[@]}"; do
                out=$D/$name.$size.$v.t
                st=$("$BIN" render "$m" "${cam[@]}" --lod "$s" --threads 1 --repeat "$repeat" \
                     --stats --out "$out.ppm" --depth-out "$out.pfm" 2>&1)
                ms[$s]+="$(sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p' <<<"$st") "
                tris[$s]+="$(sed -n 's/^lod: .*, \([0-9]*\) of .*/\1/p' <<<"$st") "
                p=$("$CMP" "$out.ppm" "$out.pfm" "$ideal.ppm" "$ideal.pfm" | sed -n 's/.*psnr=\([0-9.inf]*\).*/\1/p')
                mse[$s]+="$(awk -v p="$p" 'BEGIN { print p == "inf" ? 0 : 65025 * 10 ^ (-p / 10) }') "
            done
        done
        base=
        for s in "${settings[@]}"; do
            t=$(printf '%s\n' ${ms[$s]} | med)
            n=$(printf '%s\n' ${tris[$s]} | med)
            db=$(printf '%s\n' ${mse[$s]} | awk '{ s += $1; n++ } END { m = s / n; if (m > 0) printf "%.2f", 10 * log(65025 / m) / log(10); else print "inf" }')
            [ -z "$base" ] && base=$db
            loss=$(awk -v a="$base" -v b="$db" 'BEGIN { printf "%.2f", a - b }')
            printf '  %-12s %-8s %-10s %9.3f %8s %8s %9s\n' "$name" "$size" "$s" "$t" "$db" "$loss" "$n"
            [ -n "$csv" ] && echo "$name,$size,$s,$t,$db,$loss,$n" >> "$csv"
        done
        unset ms mse tris
    done
done
echo
if [ -x build/bench/reorder ]; then
    build/bench/reorder "${models[@]}" --frames "$((repeat + 6))"
else
    echo "-- reordering: skipped (build/bench/reorder missing: make bench builds it)"
fi
