#!/usr/bin/env bash
# tests/same_frames.sh OLD_RASTTY [NEW_RASTTY]: do two builds draw the same bytes?
#
# A tool for changes that must not change a picture (refactors, speed work): both builds
# render a matrix of scenes x methods x thread counts x kernels ($RASTTY_SIMD), the same
# arguments for both, and every output is compared byte for byte; then dumps in every
# glyph set and colour mode. Prints each case that differs and one line
# "N cases, N differ". Scenes: the generated assets, and the shared models when ../shared
# (or $RASTTY_SHARED) has them. Several minutes for the whole matrix; QUICK=1 draws a
# subset (the head and the demo, every method, one thread count and kernel besides auto).
# Not a test of make test (it needs a second build); numbers, never verdicts, are make
# bench's: this one is a yes/no for the person changing the code.
set -u
cd "$(dirname "$0")/.."
OLD=$(readlink -f "$1"); NEW=$(readlink -f "${2:-./rastty}")
S=${RASTTY_SHARED:-../shared}/models
OUT=build/same_frames; rm -rf "$OUT"; mkdir -p "$OUT"
HEAD="$S/african_head/african_head.obj --texture $S/african_head/african_head_diffuse.tga"
scenes=("demo|assets/demo.rsc" "teapot|assets/teapot.obj --texture assets/checker.png --frame"
        "torus|assets/torus.obj --frame --eye 1,2,3")
if [ -d "$S/african_head" ]; then
    scenes+=("head|$HEAD" "headnt|$S/african_head/african_head.obj")
    [ -n "${QUICK:-}" ] || scenes+=("spot|$S/spot/spot_triangulated.obj --frame"
        "bunny|$S/bunny/bunny.obj --frame" "cornell|$S/cornell_box/cornell_box.obj --frame"
        "holodeck|$S/holodeck/holodeck.obj --frame" "car|$S/sports_car/sportsCar.obj --frame"
        "empire|$S/lost_empire/lost_empire.obj --frame")
fi
methods=("def|" "unlit|--shade unlit" "flat|--shade flat" "gouraud|--shade gouraud"
 "wire|--shade wire" "wirehid|--shade wire --hidden-lines" "nearest|--filter nearest"
 "bilinear|--filter bilinear" "scan|--raster scanline" "tiled|--raster tiled"
 "affine|--persp affine" "span8|--persp span8" "span32|--persp span32" "dw|--depth w"
 "dz16|--depth z16" "drz|--depth rz" "vdepth|--view depth" "vnorm|--view normals"
 "vover|--view overdraw" "vwire|--view wire-overlay" "ssaa2|--ssaa 2" "lod|--lod auto"
 "cull|--cull back" "ortho|--ortho 3" "notex|--no-texture"
 "mix1|--shade gouraud --depth w --persp span16 --raster tiled"
 "mix2|--depth rz --persp affine --filter bilinear")
threads="1 2 3"; kernels="auto ref sse2 avx2-4 avx2-8"
[ -n "${QUICK:-}" ] && threads="1 2" && kernels="auto ref"
n=0 bad=0 skipped=0
same() { # name: compare OUT/old-NAME and OUT/new-NAME (a case the old build cannot draw,
         # such as a kernel it does not have, is skipped)
    if [ ! -s "$OUT/old-$1" ]; then skipped=$((skipped + 1)); rm -f "$OUT/new-$1"; return; fi
    n=$((n + 1))
    if ! cmp -s "$OUT/old-$1" "$OUT/new-$1"; then bad=$((bad + 1)); echo "differs: $1"; fi
    rm -f "$OUT/old-$1" "$OUT/new-$1"
}
for sc in "${scenes[@]}"; do
    sn=${sc%%|*}; sa=${sc#*|}
    for sz in 160x96 640x480; do
        for m in "${methods[@]}"; do
            mn=${m%%|*}; ma=${m#*|}
            [ "$sz" = 640x480 ] && case $sn in car|empire|bunny) [ "$mn" = def ] || continue ;; esac
            for th in $threads; do
                for k in $kernels; do
                    [ "$th" != 1 ] && [ "$k" != auto ] && case $mn in def|gouraud|dw|affine|vnorm) ;; *) continue ;; esac
                    case $sn in car|empire|holodeck) [ "$k" = auto ] || continue ;; esac
                    splits=auto; [ "$th" != 1 ] && splits="tiles slices"
                    for sp in $splits; do
                        name="$sn.$sz.$mn.t$th.$sp.$k.ppm"
                        args="$sa --size $sz $ma --threads $th --split $sp"
                        # (the kernel by $RASTTY_SIMD, which builds before --kernel read too)
                        # shellcheck disable=SC2086
                        RASTTY_SIMD=$k "$OLD" render $args --out "$OUT/old-$name" >/dev/null 2>&1
                        # shellcheck disable=SC2086
                        RASTTY_SIMD=$k "$NEW" render $args --out "$OUT/new-$name" >/dev/null 2>&1
                        same "$name"
                    done
                done
            done
        done
    done
done
for g in half quadrant sextant braille ascii; do
    for c in truecolor 256 16; do
        for b in OLD NEW; do
            "${!b}" dump assets/demo.rsc --cols 100 --rows 30 --glyphs $g --colors $c --frames 3 \
                --orbit 5 --diff --out "$OUT/$(echo $b | tr A-Z a-z)-dump.$g.$c.ans" 2>/dev/null
        done
        same "dump.$g.$c.ans"
    done
done
echo "$n cases, $bad differ ($skipped the old build cannot draw)"
[ "$bad" -eq 0 ]
