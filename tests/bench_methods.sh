#!/usr/bin/env bash
# tests/bench_methods.sh: every rendering method varied alone from the default — median
# ms/frame (rastty render --repeat --stats, one thread) and error against Mesa llvmpipe
# (build/oracle/glref, compared by build/oracle/compare: PSNR and pixels off by more than
# 8) — on the textured african_head at 160x96 and 640x480, a textured ground seen at a
# grazing angle (level and rolled), and a sphere. Textures are sampled nearest in both
# renderers (the filter is named: rastty's default is trilinear, glref's nearest). Numbers, never verdicts: `make bench` prints them.
#   tests/bench_methods.sh [--repeat N] [--csv FILE]
set -u
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
S=${RASTTY_SHARED:-../shared}/models
G=build/oracle/models
D=build/bench/methods
repeat=60 csv=
while [ $# -gt 0 ]; do
    case $1 in
    --repeat) repeat=$2; shift ;;
    --csv) csv=$2; shift ;;
    *) echo "usage: tests/bench_methods.sh [--repeat N] [--csv FILE]" >&2; exit 2 ;;
    esac
    shift
done
mkdir -p "$D"
if [ ! -x build/oracle/glref ] || [ ! -x build/oracle/compare ]; then
    echo "-- methods: skipped (build/oracle/glref missing: make oracle-build needs OSMesa)"
    exit 0
fi
/usr/bin/python3 tests/oracle/gen_models.py "$G" || exit 1
scenes=()
if [ -d "$S/african_head" ]; then
    h="$S/african_head/african_head.obj --texture $S/african_head/african_head_diffuse.tga --filter nearest"
    scenes+=("head 160x96|$h --size 160x96")
    scenes+=("head 640x480|$h --size 640x480")
    scenes+=("ground 160x96|$G/ground.obj --texture $S/floor_diffuse.tga --filter nearest --size 160x96 --eye 0,0.5,0 --target 0,0.2,-10 --shade unlit")
    scenes+=("ground 640x480|$G/ground.obj --texture $S/floor_diffuse.tga --filter nearest --size 640x480 --eye 0,0.5,0 --target 0,0.2,-10 --shade unlit")
    # rolled 20 degrees: rows are no longer lines of equal depth (on a level floor spans are
    # exact along rows, which is why floors of old games looked right)
    scenes+=("rolled 160x96|$G/ground.obj --texture $S/floor_diffuse.tga --filter nearest --size 160x96 --eye 0,0.5,0 --target 0,0.2,-10 --up 0.34,0.94,0 --shade unlit")
    scenes+=("rolled 640x480|$G/ground.obj --texture $S/floor_diffuse.tga --filter nearest --size 640x480 --eye 0,0.5,0 --target 0,0.2,-10 --up 0.34,0.94,0 --shade unlit")
else
    echo "-- methods: no shared models at $S: head and ground skipped"
fi
scenes+=("sphere 160x96|$G/sphere.obj --size 160x96 --eye 0.3,0.2,2.6")
scenes+=("sphere 640x480|$G/sphere.obj --size 640x480 --eye 0.3,0.2,2.6")
methods=("default|" "raster scanline|--raster scanline" "raster tiled|--raster tiled"
         "persp affine|--persp affine" "persp span8|--persp span8" "persp span16|--persp span16"
         "persp span32|--persp span32" "depth w|--depth w" "depth z16|--depth z16"
         "depth rz|--depth rz")
echo "-- methods: median ms/frame of $repeat (one thread) and error against Mesa llvmpipe"
printf '  %-15s %-16s %9s %9s %10s\n' scene method ms psnr_dB "off>8"
[ -n "$csv" ] && echo "scene,size,method,ms,psnr_db,frac_gt8" > "$csv"
for sc in "${scenes[@]}"; do
    name=${sc%%|*} args=${sc#*|}
    read -r -a argv <<<"$args"
    ref=$D/${name// /_}.mesa
    build/oracle/glref "${argv[@]}" --out "$ref.ppm" --depth-out "$ref.pfm" 2>/dev/null || {
        echo "  $name: reference renderer failed"; continue; }
    for m in "${methods[@]}"; do
        mname=${m%%|*} margs=${m#*|}
        out=$D/${name// /_}.${mname// /_}
        read -r -a mv <<<"$margs"
        ms=$("$BIN" render "${argv[@]}" "${mv[@]}" --threads 1 --repeat "$repeat" --stats --out "$out.ppm" \
             --depth-out "$out.pfm" 2>&1 | sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p')
        cmp=$(build/oracle/compare "$out.ppm" "$out.pfm" "$ref.ppm" "$ref.pfm" 2>/dev/null)
        psnr=$(sed -n 's/.*psnr=\([0-9.inf]*\).*/\1/p' <<<"$cmp")
        d8=$(sed -n 's/.*diff8=\([0-9]*\)\/.*/\1/p' <<<"$cmp")
        wh=$(sed -n 's/.* \([0-9]*\)x\([0-9]*\) cov.*/\1 \2/p' <<<"$cmp")
        frac=$(awk -v d="$d8" -v wh="$wh" 'BEGIN { split(wh, a, " "); printf "%.5f", d / (a[1] * a[2]) }')
        printf '  %-15s %-16s %9s %9s %10s\n' "$name" "$mname" "$ms" "$psnr" "$frac"
        [ -n "$csv" ] && echo "${name% *},${name#* },$mname,$ms,$psnr,$frac" >> "$csv"
    done
done
exit 0
