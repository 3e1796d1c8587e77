#!/usr/bin/env bash
# tests/bench.sh: `make bench` — render and terminal-output costs (numbers, never verdicts).
#   1. bytes/frame and decoded PSNR for an orbit of the shared african_head (textured,
#      2 deg/frame, 160x48 cells) on black, on the shared photo skybox, and on rastty's own sky;
#   2. key -> screen latency of the viewer behind a slow link (256 kbit/s, 1 and 4 Mbit/s,
#      unthrottled) in terminals that answer every query, only CPR and DA1 (st), only DA1,
#      and none (tests/bench_latency.sh); what reaches the screen there: each frame's decoded
#      PSNR at 256 kbit/s and 1 Mbit/s, with and without the quality floor (tests/bench_link.sh);
#   3. render time per frame of the demo scene and the big shared models;
#   4. every rendering method: ms/frame and error against Mesa (tests/bench_methods.sh);
#   5. mesh level of detail: --lod auto's bound against error and speed (tests/bench_lod.sh);
#      cost against triangles: one sphere from 10k to 4M triangles and the dense shared
#      models, clusters on and off (tests/bench_scale.sh); the viewer's first frame of the
#      1M-triangle sphere, by phase (tests/bench_first_frame.sh);
#   6. rastty against Mesa llvmpipe on the speed workloads, side by side (tests/bench_speed.sh),
#      and where the time of the head's frame goes (tests/bench_floor.sh);
#   7. the glyph sets: error, bytes and encode time, rastty against chafa (tests/bench_glyphs.sh);
#   8. where each method fails: the six stress sweeps (rastty bench --sweep NAME).
# The full methods chart takes minutes: `make chart`.
# Needs ../shared (or $RASTTY_SHARED) for the shared models; skips those parts without it.
set -eu
cd "$(dirname "$0")/.."
# the levels of detail built every time, never read from the cache (lod_cache.h): load times
# stay the simplifier's (tests/bench_scale.sh measures the cache on its own)
export RASTTY_CACHE_DIR=
BIN=${RASTTY_BIN:-./rastty}
S=${RASTTY_SHARED:-../shared}/models
S=$(cd "$(dirname "$S")" 2>/dev/null && echo "$PWD/$(basename "$S")" || echo "$S")
A=$PWD/assets
D=build/bench
mkdir -p "$D"
sky_files() { local p=$1 e=$2; echo "$p/posx.$e $p/negx.$e $p/posy.$e $p/negy.$e $p/posz.$e $p/negz.$e"; }
echo "== rastty bench ($(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(uname -m))"
if [ -d "$S/african_head" ]; then
    head="model $S/african_head/african_head.obj texture $S/african_head/african_head_diffuse.tga
camera 0 0 3 target 0 0 0"
    printf '%s\n' "$head" > $D/head_black.rsc
    printf '%s\nsky %s\n' "$head" "$(sky_files "$S/skybox" jpg)" > $D/head_photo_sky.rsc
    printf '%s\nsky %s\n' "$head" "$A/sky_posx.png $A/sky_negx.png $A/sky_posy.png $A/sky_negy.png $A/sky_posz.png $A/sky_negz.png" > $D/head_builtin_sky.rsc
    echo "-- terminal bytes: african_head orbit, 2 deg/frame, 180 frames, 160x48 cells"
    "$BIN" bench $D/head_black.rsc $D/head_photo_sky.rsc $D/head_builtin_sky.rsc \
        --cols 160 --rows 48 --frames 180 --orbit 2
else
    echo "-- skipped terminal-bytes benchmark: no shared models at $S"
fi
echo
tests/bench_latency.sh
echo
tests/bench_link.sh
echo
echo "-- render time: demo scene and shared models, 160x48 and 320x96 cells, 36 frames"
models=("assets/demo.rsc")
for m in sports_car/sportsCar.obj lost_empire/lost_empire.obj bunny/bunny.obj; do
    [ -f "$S/$m" ] && models+=("$S/$m")
done
for size in "160 48" "320 96"; do
    set -- $size
    "$BIN" bench "${models[@]}" --cols "$1" --rows "$2" --frames 36 --orbit 10 |
        grep -E '^[^ ].*frames' || true
done
echo
tests/bench_methods.sh
echo
tests/bench_lod.sh
echo
tests/bench_scale.sh
echo
tests/bench_first_frame.sh
echo
tests/bench_speed.sh
tests/bench_floor.sh
echo
tests/bench_glyphs.sh
echo
echo "-- where methods fail: rastty bench --sweep NAME at 160x96 (deterministic: no timing)"
for s in grazing depthrange magnitude sliver nearplane minification; do
    "$BIN" bench --sweep "$s"
    echo
done
