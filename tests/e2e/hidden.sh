#!/usr/bin/env bash
# hidden.sh: --hidden-cull and --cluster-cull (both on by default; render/frontend.h,
# "Hidden", and cluster_cull.h) never change a picture of a real file — the sports car, the
# bunny and two glTF samples with textures, normal maps and emission (../shared; skipped
# without it: tests/unit/test_hidden.c and test_clusters.c hold generated meshes to the
# same) — in shading modes, supersampling, culling and thread splits: every colour and depth
# byte the same as with both off; while they drop triangles and whole clusters (--stats
# "hidden N" on both lines). (The built-in models hide too little at these sizes to tell.)
source "$(dirname "$0")/lib/common.sh"

OPTS=("" "--shade gouraud" "--shade flat" "--raster scanline" "--persp span16" "--ssaa 2"
      "--cull back" "--view normals" "--depth z16" "--threads 2 --split slices"
      "--threads 2 --split tiles")

# same MODEL...: every model from one eye at 80x48 with each of OPTS, on and off
same() {
    local m o n=0 hidden=0 clusters=0 st
    for m in "$@"; do
        for o in "${OPTS[@]}"; do
            # shellcheck disable=SC2086 # (o: words)
            st=$("$BIN" render "$m" --eye 0.5,0.364,0.8 --frame --size 80x48 --threads 1 $o \
                --stats --out $OUT/on.ppm --depth-out $OUT/on.pfm 2>&1) || { echo "$m $o: failed"; return 1; }
            # shellcheck disable=SC2086
            "$BIN" render "$m" --eye 0.5,0.364,0.8 --frame --size 80x48 --threads 1 $o \
                --hidden-cull off --cluster-cull off --out $OUT/off.ppm --depth-out $OUT/off.pfm \
                2>/dev/null || return 1
            cmp -s $OUT/on.ppm $OUT/off.ppm && cmp -s $OUT/on.pfm $OUT/off.pfm ||
                { echo "DIFFER: $m $o"; return 1; }
            hidden=$((hidden + $(sed -n 's/^tris in .* hidden \([0-9]*\),.*/\1/p' <<<"$st" | tail -n 1)))
            clusters=$((clusters + $(sed -n 's/^clusters: .* hidden \([0-9]*\)).*/\1/p' <<<"$st" |
                tail -n 1 | grep . || echo 0)))
            n=$((n + 1))
        done
    done
    echo "$n pictures the same; $hidden triangles hidden in all, $clusters whole clusters"
    [ "$hidden" -gt 0 ] && [ "$clusters" -gt 0 ]
}
shared() {
    same "$SHARED/sports_car/sportsCar.obj" "$SHARED/bunny/bunny.obj" \
        "$SHARED/gltf-samples/ToyCar/glTF/ToyCar.gltf" \
        "$SHARED/gltf-samples/BoomBox/glTF/BoomBox.gltf"
}
if [ -f "$SHARED/sports_car/sportsCar.obj" ] && [ -f "$SHARED/bunny/bunny.obj" ] &&
    [ -f "$SHARED/gltf-samples/ToyCar/glTF/ToyCar.gltf" ] &&
    [ -f "$SHARED/gltf-samples/BoomBox/glTF/BoomBox.gltf" ]; then
    check hidden_and_cluster_cull_change_no_byte_of_the_shared_models shared
else
    skip hidden_and_cluster_cull_change_no_byte_of_the_shared_models "no $SHARED (car, bunny, ToyCar, BoomBox)"
fi
finish
