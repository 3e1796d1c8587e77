#!/usr/bin/env bash
# cli.sh (issue 11): the command line's rough edges — textures found beside a model, the
# light conventions of render, what dump writes to files.
source "$(dirname "$0")/lib/common.sh"

HEAD=$SHARED/african_head
# A model without an MTL gets the texture beside it by name; --no-texture turns that off;
# a corrupt texture found that way is an error that says how to avoid it.
convention() {
    local d=$OUT/conv; mkdir -p $d
    grep -v '^mtllib\|^usemtl' assets/sphere.obj > $d/ball.obj
    "$BIN" render $d/ball.obj --frame --out $d/plain.ppm || return 1
    cp assets/checker.png $d/ball_diffuse.png
    "$BIN" render $d/ball.obj --frame --out $d/found.ppm || return 1
    "$BIN" render $d/ball.obj --frame --texture assets/checker.png --out $d/given.ppm || return 1
    "$BIN" render $d/ball.obj --frame --no-texture --out $d/off.ppm || return 1
    cmp -s $d/plain.ppm $d/found.ppm && { echo "ball_diffuse.png was not used"; return 1; }
    cmp $d/found.ppm $d/given.ppm || return 1
    cmp $d/plain.ppm $d/off.ppm || return 1
    printf 'not an image' > $d/ball_diffuse.png
    local err; err=$("$BIN" render $d/ball.obj --out $d/x.ppm 2>&1)
    echo "corrupt: $err"
    echo "$err" | grep -q "ball_diffuse.png.*--no-texture" || return 1
    "$BIN" render $d/ball.obj --no-texture --out $d/x.ppm
}
check textures_found_beside_a_model convention

shared_head() {
    "$BIN" render "$HEAD/african_head.obj" --out $OUT/head_conv.ppm &&
        "$BIN" render "$HEAD/african_head.obj" --texture "$HEAD/african_head_diffuse.tga" \
            --out $OUT/head_given.ppm && cmp $OUT/head_conv.ppm $OUT/head_given.ppm
}
if [ -f "$HEAD/african_head_diffuse.tga" ]; then
    check shared_head_finds_its_diffuse_texture shared_head
else
    skip shared_head_finds_its_diffuse_texture "no shared african_head (../shared absent)"
fi

finish
