#!/usr/bin/env bash
# first_frame.sh (issue 24: a big file's first frame sooner): the viewer makes its default sky
# on a thread of its own while the models load, toward the command line's first light; the
# first frame it draws must be the picture `rastty render` draws with that sky — for a model
# (the sky made ahead is used) and for a scene whose own light moves the sun (the sky made
# ahead is dropped and made again). The frames are the viewer's own framebuffers
# (RASTTY_FRAME_PPM, include/viewer/view_frames.h; each file appears whole, renamed into
# place), compared byte for byte.
source "$(dirname "$0")/lib/common.sh"

T=$PWD/assets/teapot.obj
NAMES=(first_frame_sky_made_ahead_is_renders_sky first_frame_sky_of_a_scene_with_its_own_sun)
if ! have_tmux; then
    for n in "${NAMES[@]}"; do skip "$n" "tmux not installed"; done
    finish
fi

# same_as_render NAME MODEL LIGHT...: the viewer's first framebuffer (80x24 cells, no
# status line: 80x48 pixels) against render's at that size, framed; the light fixed in the
# world ("light = world" in a config file of the test's own: the scene's light, or 1,1,1)
same_as_render() {
    local name=$1 model=$2 dir=$OUT/$1; shift 2
    rm -rf "$dir" && mkdir -p "$dir/cfg/rastty"
    echo "light = world" > "$dir/cfg/rastty/config"
    tm new-session -d -s "$name" -x 80 -y 24 \
        "XDG_CONFIG_HOME=$PWD/$dir/cfg RASTTY_FRAME_PPM=$PWD/$dir $(printf '%q ' "$BIN" --colors truecolor --no-hud --lod off "$@" "$model"); sleep 60"
    wait_for 30 test -f "$dir/fb-00001.ppm" || { ls "$dir"; return 1; }
    tm kill-session -t "$name"
    XDG_CONFIG_HOME=$PWD/$dir/cfg "$BIN" render "$model" --size 80x48 --frame --lod off \
        --sky procedural "$@" --out "$dir/render.ppm" 2>/dev/null || return 1
    cmp "$dir/fb-00001.ppm" "$dir/render.ppm" && echo "$(ppmstat "$dir/render.ppm")"
}
sky_ahead() { same_as_render ahead "$T" --light 1,1,1; }
sky_own_sun() { # the sun low in the sky the camera sees, right of the teapot
    printf 'model %s\nlight 0.25 0.1 -1\n' "$T" > "$OUT/sun.rsc"
    same_as_render own_sun "$PWD/$OUT/sun.rsc"
}
check first_frame_sky_made_ahead_is_renders_sky sky_ahead
check first_frame_sky_of_a_scene_with_its_own_sun sky_own_sun
finish
