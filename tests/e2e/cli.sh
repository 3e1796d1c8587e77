#!/usr/bin/env bash
# cli.sh (issue 11): the command line's rough edges — textures found beside a model, the
# light conventions of render and dump (the viewer's light), what dump writes to files,
# wireframe at terminal sizes (--wire).
source "$(dirname "$0")/lib/common.sh"

HEAD=$SHARED/african_head
# -h is --help
short_help() {
    "$BIN" -h > $OUT/h.txt && "$BIN" --help > $OUT/help.txt && cmp $OUT/h.txt $OUT/help.txt &&
        grep -q -- "--help, -h" $OUT/help.txt && "$BIN" render -h | cmp - $OUT/help.txt
}
check dash_h_is_help short_help

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
    # a file found there that is no image: a warning naming it, and the model untextured
    printf 'not an image' > $d/ball_diffuse.png
    local err; err=$("$BIN" render $d/ball.obj --frame --out $d/x.ppm 2>&1) || { echo "$err"; return 1; }
    echo "corrupt: $err"
    echo "$err" | grep -q "^warning: .*ball_diffuse.png.*found beside the model; drawn untextured" || return 1
    cmp $d/plain.ppm $d/x.ppm
}
check textures_found_beside_a_model convention

# found by name: the diffuse texture and, by the same habit, the normal map beside it
# (african_head_nm.tga, object space); a --texture alone draws without the normal map
shared_head() {
    "$BIN" render "$HEAD/african_head.obj" --out $OUT/head_conv.ppm &&
        "$BIN" render "$HEAD/african_head.obj" --texture "$HEAD/african_head_diffuse.tga" \
            --normal-map "$HEAD/african_head_nm.tga" --out $OUT/head_given.ppm &&
        cmp $OUT/head_conv.ppm $OUT/head_given.ppm || return 1
    "$BIN" render "$HEAD/african_head.obj" --texture "$HEAD/african_head_diffuse.tga" \
        --out $OUT/head_plain.ppm || return 1
    if cmp -s $OUT/head_conv.ppm $OUT/head_plain.ppm; then echo "the normal map changed nothing"; return 1; fi
}
if [ -f "$HEAD/african_head_diffuse.tga" ]; then
    check shared_head_finds_its_diffuse_texture_and_normal_map shared_head
else
    skip shared_head_finds_its_diffuse_texture_and_normal_map "no shared african_head (../shared absent)"
fi

# dump to a file or a pipe: truecolor whatever TERM says (unless --colors), plain LF lines
dump_files() {
    local term
    for term in dumb xterm vt100 ""; do
        TERM=$term "$BIN" dump assets/cube.obj --frame --out $OUT/t.ans || return 1
        grep -q $'\e\[38;2;\|\e\[48;2;' $OUT/t.ans || { echo "TERM='$term': not truecolor"; return 1; }
        TERM=$term "$BIN" dump assets/cube.obj --frame > $OUT/p.ans || return 1
        cmp $OUT/t.ans $OUT/p.ans || { echo "TERM='$term': the pipe differs from the file"; return 1; }
    done
    TERM=xterm-direct "$BIN" dump assets/cube.obj --frame --colors 256 --out $OUT/c.ans || return 1
    grep -q $'\e\[48;5;' $OUT/c.ans && ! grep -q $'\e\[48;2;' $OUT/c.ans || { echo "--colors 256 ignored"; return 1; }
    if grep -q $'\r' $OUT/t.ans; then echo "CR in a .ans file"; return 1; fi
    [ "$(grep -c '' $OUT/t.ans)" -ge 23 ] || { echo "no line ends"; return 1; }
}
check dump_to_files_is_truecolor_with_lf_lines dump_files

# --out FILE.cast: asciicast v2 — a JSON header, one JSON event per frame at k / --fps
# seconds, whose bytes replay to the last frame.
cast() {
    "$BIN" dump assets/cube.obj --frame --cols 60 --rows 20 --frames 12 --orbit 8 --diff \
        --fps 10 --out $OUT/spin.cast --ppm-dir $OUT || return 1
    /usr/bin/python3 - $OUT/spin.cast $OUT/replay.ans <<'PY' || return 1
import json, sys
lines = open(sys.argv[1], encoding="utf-8").read().splitlines()
h = json.loads(lines[0])
assert h["version"] == 2 and h["width"] == 60 and h["height"] == 20, h
ev = [json.loads(l) for l in lines[1:]]
assert all(e[1] == "o" for e in ev)
times = [e[0] for e in ev]
assert times == sorted(times), times
frames = [e for e in ev if e[2].startswith("\x1b[H")]
assert [round(e[0], 6) for e in frames] == [round(k / 10, 6) for k in range(12)], times
open(sys.argv[2], "w", encoding="utf-8", newline="").write("".join(e[2] for e in ev))
print("cast: %d events over %.1f s" % (len(ev), times[-1]))
PY
    "$BIN" ansi2ppm $OUT/replay.ans --out $OUT/replay.ppm && cmp $OUT/replay.ppm $OUT/frame-0011.ppm || return 1
    # and `asciinema play` (when installed) leaves the last frame on a terminal of that size
    if command -v asciinema >/dev/null && have_tmux; then
        tm new-session -d -s cast -x 60 -y 20 "asciinema play $OUT/spin.cast; touch $OUT/played; sleep 30"
        wait_for 20 test -f $OUT/played || { echo "asciinema play did not finish"; return 1; }
        capture cast $OUT/played.ans
        "$BIN" ansi2ppm $OUT/played.ans --out $OUT/played.ppm &&
            cmp $OUT/played.ppm $OUT/frame-0011.ppm || { echo "asciinema play shows another picture"; return 1; }
    else
        echo "(asciinema or tmux not installed: checked with python's json only)"
    fi
}
check dump_out_cast_is_asciicast_v2 cast

# A dump is what the viewer shows (issue 25): the headlight by default, so an orbit is lit
# from every side (with the fixed light the far side was near black); --light 1,1,1 is the
# fixed light still. Mean brightness of the sphere's frames at 0 and 180 degrees.
mean_of() { /usr/bin/python3 -c '
import sys
d = open(sys.argv[1], "rb").read()
parts = d.split(maxsplit=4)
px = parts[4]
print(int(sum(px) / len(px)))' "$1"; }
dump_light() {
    local d=$OUT/light; mkdir -p $d/head $d/fixed
    "$BIN" dump assets/sphere.obj --frame --cols 40 --rows 20 --frames 3 --orbit 90 \
        --ppm-dir $d/head --out $d/head.ans || return 1
    "$BIN" dump assets/sphere.obj --frame --cols 40 --rows 20 --frames 3 --orbit 90 \
        --light 1,1,1 --ppm-dir $d/fixed --out $d/fixed.ans || return 1
    local h0 h2 f0 f2
    h0=$(mean_of $d/head/frame-0000.ppm); h2=$(mean_of $d/head/frame-0002.ppm)
    f0=$(mean_of $d/fixed/frame-0000.ppm); f2=$(mean_of $d/fixed/frame-0002.ppm)
    echo "mean brightness, 0 and 180 degrees: default $h0 $h2; --light 1,1,1 $f0 $f2"
    [ $((h2 * 10)) -ge $((h0 * 8)) ] && [ $((f2 * 10)) -lt $((f0 * 6)) ]
}
check dump_lights_an_orbit_from_every_side_as_the_viewer dump_light

# Wireframe at terminal sizes (issue 25 item 7): the shared head's 2.5k triangles at 160x96
# are a white blob with every edge (--wire all lights ~2100 pixels, all of its silhouette);
# the default, auto, draws its outline (silhouettes, creases, borders: ~560): eyes, mouth,
# jaw and neck are lines again. The cube keeps every edge, diagonals too (the same bytes).
wire_auto() {
    local h=$HEAD/african_head.obj w a
    "$BIN" render assets/cube.obj --shade wire --size 160x96 --out $OUT/cube_auto.ppm &&
        "$BIN" render assets/cube.obj --shade wire --wire all --size 160x96 --out $OUT/cube_all.ppm &&
        cmp $OUT/cube_auto.ppm $OUT/cube_all.ppm || { echo "the cube lost edges in auto"; return 1; }
    [ -f "$h" ] || { echo "(no shared head: the cube only)"; return 0; }
    for w in all auto outline; do
        "$BIN" render "$h" --shade wire --wire $w --size 160x96 --out $OUT/head_$w.ppm || return 1
    done
    cmp $OUT/head_auto.ppm $OUT/head_outline.ppm || { echo "auto is not the outline"; return 1; }
    set -- $(ppmstat $OUT/head_all.ppm) ; w=$3
    set -- $(ppmstat $OUT/head_auto.ppm); a=$3
    echo "head 160x96: --wire all lights $w pixels, auto $a"
    [ $((a * 3)) -lt "$w" ] && [ "$a" -gt 200 ]
}
check wire_auto_draws_what_a_terminal_can_show wire_auto

finish
