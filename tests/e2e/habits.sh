#!/usr/bin/env bash
# habits.sh (issue 25 item 8): habits users bring from chafa, timg, viu and 3D viewers —
# `-` for a model on standard input and `--out -` for standard output, ansi2ppm on a tmux
# capture with the status line or the help in it, hjkl, a key that hides the status line,
# pan (shift-drag, middle-drag, shift-arrows), and the cell aspect.
source "$(dirname "$0")/lib/common.sh"

ABS_BIN=$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")

# A model on standard input draws the same bytes as the file, for render and dump, its format
# found by content (binary STL, glTF, OBJ), its MTL and texture found in the current folder.
stdin_models() {
    local d=$OUT/stdin; mkdir -p $d
    cp assets/cube.obj assets/cube.mtl assets/uvgrid.png $d/ || return 1
    (cd $d && "$ABS_BIN" render cube.obj --out file.png && "$ABS_BIN" render - --out pipe.png < cube.obj) || return 1
    cmp $d/file.png $d/pipe.png || { echo "render: the pipe differs from the file"; return 1; }
    # the texture counts: the same model elsewhere (no uvgrid.png there) draws differently
    (cd $OUT && "$ABS_BIN" render - --out $PWD/stdin/elsewhere.png < stdin/cube.obj 2>/dev/null)
    cmp -s $d/file.png $d/elsewhere.png && { echo "the texture was not read from ."; return 1; }
    (cd $d && "$ABS_BIN" dump cube.obj --cols 40 --rows 12 > file.ans && cat cube.obj | "$ABS_BIN" dump - --cols 40 --rows 12 > pipe.ans) || return 1
    cmp $d/file.ans $d/pipe.ans || { echo "dump: the pipe differs from the file"; return 1; }
    # a binary STL and a glTF: no name to go by
    python3 - $d <<'EOF' || return 1
import struct, sys, json, base64
d = sys.argv[1]
tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
with open(d + "/t.stl", "wb") as f:
    f.write(b"\0" * 80 + struct.pack("<I", 1) + struct.pack("<3f", 0, 0, 1))
    for v in tri: f.write(struct.pack("<3f", *v))
    f.write(b"\0\0")
pos = b"".join(struct.pack("<3f", *v) for v in tri)
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                    "min": [0, 0, 0], "max": [1, 1, 0]}],
     "bufferViews": [{"buffer": 0, "byteLength": 36}],
     "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64," + base64.b64encode(pos).decode()}]}
open(d + "/t.gltf", "w").write(json.dumps(g))
EOF
    local m
    for m in t.stl t.gltf; do
        "$BIN" render $d/$m --out $d/$m.file.ppm && "$BIN" render - --out $d/$m.pipe.ppm < $d/$m || return 1
        cmp $d/$m.file.ppm $d/$m.pipe.ppm || { echo "$m: the pipe differs from the file"; return 1; }
    done
}
check a_model_on_stdin_draws_as_its_file stdin_models

# --out - writes the image to standard output: PNG by default, PPM with --format ppm, the
# same bytes as the file; dump --out - is dump's standard output; ansi2ppm --out - too
stdout_images() {
    local d=$OUT/stdout; mkdir -p $d
    "$BIN" render assets/teapot.obj --out $d/f.png && "$BIN" render assets/teapot.obj --out - > $d/p.png || return 1
    cmp $d/f.png $d/p.png || { echo "--out -: not the PNG file's bytes"; return 1; }
    "$BIN" render assets/teapot.obj --out $d/f.ppm && "$BIN" render assets/teapot.obj --out - --format ppm | cat > $d/p.ppm || return 1
    cmp $d/f.ppm $d/p.ppm || { echo "--out - --format ppm: not the PPM file's bytes"; return 1; }
    "$BIN" dump assets/teapot.obj --cols 30 --rows 10 --out $d/f.ans && "$BIN" dump assets/teapot.obj --cols 30 --rows 10 --out - > $d/p.ans || return 1
    cmp $d/f.ans $d/p.ans || { echo "dump --out -: not the file's bytes"; return 1; }
    "$BIN" ansi2ppm $d/f.ans --out $d/a.png && "$BIN" ansi2ppm $d/f.ans --out - > $d/a2.png || return 1
    cmp $d/a.png $d/a2.png || { echo "ansi2ppm --out -: not the file's bytes"; return 1; }
    "$BIN" ansi2ppm - --out $d/a3.png < $d/f.ans && cmp $d/a.png $d/a3.png || { echo "ansi2ppm -: not the file's bytes"; return 1; }
    # a file's format is its extension: --format with a file name is a usage error
    "$BIN" render assets/teapot.obj --out $d/x.png --format ppm 2> $d/fmt.err; local rc=$?
    [ $rc -eq 2 ] && grep -q -- "--format ppm is for --out -" $d/fmt.err || { echo "rc $rc: $(cat $d/fmt.err)"; return 1; }
}
check out_dash_writes_the_same_bytes_to_stdout stdout_images

# binary never goes to a terminal (as chafa and convert refuse), stdin that is a terminal is
# not waited on, bad bytes on stdin are named <stdin>; each exit 2 with one clear line
refusals() {
    local d=$OUT/refuse; mkdir -p $d
    tm new-session -d -s rf -x 150 -y 10 \
        "$(printf '%q ' "$BIN") render assets/cube.obj --out - 2> $d/png.err; echo \$? > $d/png.rc; $(printf '%q ' "$BIN") render - --out $d/x.png 2> $d/tty.err; echo \$? > $d/tty.rc; sleep 60"
    wait_for 10 test -s $d/tty.rc || { echo "no exit (waiting for typing?)"; return 1; }
    echo "png: $(cat $d/png.rc) $(cat $d/png.err)"; echo "stdin: $(cat $d/tty.rc) $(cat $d/tty.err)"
    [ "$(cat $d/png.rc)" = 2 ] && grep -q "^rastty render: --out -: standard output is a terminal; refusing to write a PNG image to it" $d/png.err || return 1
    [ "$(cat $d/tty.rc)" = 2 ] && grep -q "^<stdin>: cannot read: standard input is a terminal" $d/tty.err || return 1
    [ ! -e $d/x.png ] || return 1
    printf 'v 0 0 0\nv 1 x 0\n' | "$BIN" render - --out $d/x.png 2> $d/bad.err; local rc=$?
    echo "bad: $rc $(cat $d/bad.err)"
    [ $rc -eq 2 ] && grep -q "^<stdin>:2: " $d/bad.err || return 1
    "$BIN" render - --out $d/x.png < /dev/null 2> $d/empty.err; rc=$?
    echo "empty: $rc $(cat $d/empty.err)"
    [ $rc -eq 2 ] && grep -q "^<stdin>" $d/empty.err || return 1
    "$BIN" view - - < /dev/null 2> $d/twice.err; rc=$?
    [ $rc -eq 2 ] && grep -q "standard input) may be given once" $d/twice.err || { echo "twice: $rc $(cat $d/twice.err)"; return 1; }
}
if have_tmux; then check binary_never_to_a_terminal_and_stdin_errors_say_stdin refusals
else skip binary_never_to_a_terminal_and_stdin_errors_say_stdin "tmux not installed"; fi

# the viewer takes its model from a pipe and its keys from the terminal
viewer_stdin() {
    tm new-session -d -s vs -x 80 -y 25 \
        "cat assets/sphere.obj | $(printf '%q ' "$BIN") --colors truecolor - --background 0,0,0; echo EXIT=\$? > $OUT/vs.exit; sleep 60"
    wait_for 15 hud_has vs " fps" || { echo "no status line: $(status_line vs)"; return 1; }
    still_after vs 0 || return 1
    hud_has vs "stdin" || { echo "status line lacks stdin: $(status_line vs)"; return 1; }
    keys vs w || return 1
    tm send-keys -t vs q
    wait_for 10 test -s $OUT/vs.exit || { echo "q did not quit"; return 1; }
    grep -q EXIT=0 $OUT/vs.exit
}
if have_tmux; then check the_viewer_reads_a_model_from_a_pipe_and_keys_from_the_terminal viewer_stdin
else skip the_viewer_reads_a_model_from_a_pipe_and_keys_from_the_terminal "tmux not installed"; fi

# ansi2ppm decodes a real capture of the viewer, status line and help box included: the
# picture's rows decode as the capture without them does, the status line's cells are its
# grey, and the help's text cells are counted on stderr
start() { # session cols rows args...
    local s=$1 c=$2 r=$3; shift 3
    tm new-session -d -s "$s" -x "$c" -y "$r" \
        "$(printf '%q ' "$BIN" --colors truecolor "$@"); echo EXIT=\$? > $OUT/$s.exit; sleep 120"
    wait_for 15 hud_has "$s" " fps" || { echo "no status line: $(status_line "$s")"; return 1; }
}
captures() {
    local s=cap d=$OUT/cap; mkdir -p $d
    start $s 80 24 assets/teapot.obj --background 0,0,0 && still_after $s 0 || return 1
    tm capture-pane -t $s -e -N -p > $d/full.ans
    head -n 23 $d/full.ans > $d/pic.ans
    "$BIN" ansi2ppm $d/pic.ans --out $d/pic.ppm || return 1
    "$BIN" ansi2ppm $d/full.ans --out $d/full.ppm 2> $d/full.err || { cat $d/full.err; return 1; }
    echo "status line: $(cat $d/full.err)"
    grep -q "text cells (a status line, a help box) drawn as their background colour" $d/full.err || return 1
    python3 - $d/pic.ppm $d/full.ppm <<'EOF2' || return 1
import sys
def ppm(p):
    b = open(p, "rb").read()
    head = b.split(b"\n", 3)
    w, h = map(int, head[1].split())
    return w, h, head[3]
w, h, pic = ppm(sys.argv[1])
W, H, full = ppm(sys.argv[2])
assert (W, H) == (80, 48) and (w, h) == (80, 46), (W, H, w, h)
assert full[:len(pic)] == pic, "the picture's rows differ"
status = full[len(pic):]
grey = sum(1 for i in range(0, len(status), 3) if status[i:i + 3] == bytes([229, 229, 229]))
print("status line: %d of %d pixels grey" % (grey, len(status) // 3))
assert grey >= len(status) // 3 - 2  # (the viewer leaves the last column alone)
EOF2
    tm send-keys -t $s "$HELP_KEY"
    wait_for 10 tm_has $s "quit" || { echo "no help box"; return 1; }
    tm capture-pane -t $s -e -N -p > $d/help.ans
    "$BIN" ansi2ppm $d/help.ans --out $d/help.png 2> $d/help.err || { cat $d/help.err; return 1; }
    echo "help: $(cat $d/help.err)"
    local n; n=$(sed -n 's/.*: \([0-9]*\) text cells.*/\1/p' $d/help.err)
    [ "${n:-0}" -gt 200 ]
}
tm_has() { tm capture-pane -t "$1" -p | grep -q "$2"; }
HELP_KEY=?
if have_tmux; then check ansi2ppm_decodes_a_capture_with_the_status_line_and_the_help captures
else skip ansi2ppm_decodes_a_capture_with_the_status_line_and_the_help "tmux not installed"; fi

# the picture of session $1 (status line dropped unless $3 = all) as $OUT/$2.ppm; its stats
picture() {
    local rows; rows=$(tm display -p -t "$1" '#{pane_height}')
    [ "${3:-}" = all ] || rows=$((rows - 1))
    capture "$1" "$OUT/$2.ans" $rows
    decode "$OUT/$2.ans" "$OUT/$2.ppm" 2>/dev/null && ppmstat "$OUT/$2.ppm" 0,0,0
}
same_picture() { cmp -s "$OUT/$1.ppm" "$OUT/$2.ppm"; }

# h j k l turn exactly as the arrows do (a tap turns for the same time); h no longer opens
# the help, ? does, and the status line says so
vi_keys() {
    local s=vi pair k a
    start $s 80 25 assets/teapot.obj --background 0,0,0 && still_after $s 0 || return 1
    picture $s home > /dev/null
    hud_has $s "?: help" || { echo "status line: $(status_line $s)"; return 1; }
    for pair in h:Left j:Down k:Up l:Right; do
        k=${pair%%:*} a=${pair#*:}
        # (a press within 0.5 s of the last one of its command is auto-repeat: it moves less)
        keys $s r && nap 0.6 && keys $s $k || return 1
        picture $s "vi-$k" > /dev/null
        keys $s r && nap 0.6 && keys $s $a || return 1
        picture $s "vi-$a" > /dev/null
        same_picture "vi-$k" "vi-$a" || { echo "$k is not $a"; return 1; }
        same_picture "vi-$k" home && { echo "$k did not turn"; return 1; }
    done
    echo "h j k l drew the pictures Left Down Up Right draw"
    tm capture-pane -t $s -p | grep -q "this help" && { echo "h opened the help"; return 1; }
    keys $s '?' || return 1
    tm capture-pane -t $s -p | grep -q "this help" || { echo "? did not open the help"; return 1; }
    keys $s '?' || return 1
    tm capture-pane -t $s -p | grep -q "this help" && { echo "? did not close the help"; return 1; }
    return 0
}
if have_tmux; then check hjkl_turn_as_the_arrows_and_question_mark_is_the_help vi_keys
else skip hjkl_turn_as_the_arrows_and_question_mark_is_the_help "tmux not installed"; fi

# H hides the status line (the picture takes the last row) and shows it again; --no-hud
# starts hidden
hud_key() {
    local s=hud
    start $s 80 25 assets/sphere.obj && still_after $s 0 || return 1
    set -- $(picture $s with all); local rows_with=$2
    tm send-keys -t $s H
    wait_for 10 no_status $s || { echo "H: the status line stayed: $(status_line $s)"; return 1; }
    # no #N to wait for without a status line: the picture's last row fills in
    wait_for 10 bottom_drawn $s || { echo "the last row stayed empty"; return 1; }
    set -- $(picture $s without all)
    echo "status line: picture 80x$rows_with (area $3 with it); H: 80x$2"
    tm send-keys -t $s H
    wait_for 10 hud_has $s "status line on" || { echo "H again: $(status_line $s)"; return 1; }
    tm kill-session -t $s
    tm new-session -d -s nh -x 80 -y 25 "$(printf '%q ' "$BIN") --colors truecolor --no-hud assets/sphere.obj; sleep 60"
    wait_for 10 bottom_drawn nh || return 1
    no_status nh || return 1
    tm send-keys -t nh H
    wait_for 10 hud_has nh " fps" || { echo "--no-hud then H: no status line"; return 1; }
}
no_status() { [[ $(status_line "$1") != *" fps"* && $(status_line "$1") != *"?: help"* ]]; }
# the last row holds the picture (the viewer's sky, in colour), not the status line
bottom_drawn() { tm capture-pane -t "$1" -e -p | tail -n 1 | grep -q '38;2;'; }
if have_tmux; then check shift_h_hides_and_shows_the_status_line hud_key
else skip shift_h_hides_and_shows_the_status_line "tmux not installed"; fi

# pan: a shift-drag or a middle-drag to the right moves the model right (it follows the
# mouse), Shift-Right moves the camera right (the model left, as d does); a plain drag
# still orbits
pan() {
    local s=pan
    start $s 100 31 assets/teapot.obj --background 0,0,0 || return 1
    still_after $s 0 || return 1
    set -- $(picture $s p0); local x0=$4 y0=$5
    # shift (+4): press 4 at 40,15, motion 36 to 60,15 (20 columns right), release
    tm send-keys -t $s -H 1b 5b 3c 34 3b 34 30 3b 31 35 4d            # ESC[<4;40;15M
    tm send-keys -t $s -H 1b 5b 3c 33 36 3b 36 30 3b 31 35 4d         # ESC[<36;60;15M
    tm send-keys -t $s -H 1b 5b 3c 34 3b 36 30 3b 31 35 6d            # ESC[<4;60;15m
    wait_for 10 moved $s p1 x "$x0" 15 || { echo "shift-drag: centroid x $x0 -> $(cut -d' ' -f4 <<< "$(picture $s p1)")"; return 1; }
    set -- $(picture $s p1); local x1=$4 y1=$5
    echo "shift-drag 20 columns right: centroid x $x0 -> $x1 (y $y0 -> $y1)"
    keys $s r || return 1
    set -- $(picture $s p2); local x2=$4
    # the middle button (1): press at 50,20, motion 33 to 50,10 (10 rows up), release
    tm send-keys -t $s -H 1b 5b 3c 31 3b 35 30 3b 32 30 4d            # ESC[<1;50;20M
    tm send-keys -t $s -H 1b 5b 3c 33 33 3b 35 30 3b 31 30 4d         # ESC[<33;50;10M
    tm send-keys -t $s -H 1b 5b 3c 31 3b 35 30 3b 31 30 6d            # ESC[<1;50;10m
    wait_for 10 moved $s p3 y "$y0" -10 || { echo "middle-drag up: no move up"; return 1; }
    set -- $(picture $s p3); echo "middle-drag 10 rows up: centroid y $y0 -> $5, x $x2 -> $4"
    keys $s r S-Right S-Right || return 1
    set -- $(picture $s p4); echo "Shift-Right twice: centroid x $x2 -> $4"
    awk -v a="$x2" -v b="$4" 'BEGIN { exit !(b < a - 2) }' || { echo "Shift-Right did not move the model left"; return 1; }
}
# moved S NAME x|y FROM BY: the centroid's x or y moved by at least BY pixels (negative: down
# to FROM+BY) from FROM, in a still picture
moved() {
    [ "$(frame_no "$1")" -gt 0 ] || return 1
    local st; st=$(picture "$1" "$2") || return 1
    set -- $st "$3" "$4" "$5"
    local v=$4; [ "$7" = y ] && v=$5
    awk -v v="$v" -v f="$8" -v by="$9" 'BEGIN { exit !((by > 0 && v > f + by) || (by < 0 && v < f + by)) }'
}
if have_tmux; then check shift_and_middle_drag_and_shift_arrows_pan pan
else skip shift_and_middle_drag_and_shift_arrows_pan "tmux not installed"; fi

# cell aspect: a terminal whose cells are 10x22 pixels (told by ESC[16t's answer, or by
# TIOCGWINSZ's pixel fields) gets the picture --cell-aspect 2.2 draws, byte for byte, and
# not the 1:2 one: the sphere is 1.1 times as many pixels wide as tall, so it is round on
# the screen
FILTER=tests/e2e/lib/termfilter.py
aspect_picture() { # session name termfilter-args... -- viewer-args...
    local s=$1 name=$2 f=() ; shift 2
    while [ "$1" != -- ]; do f+=("$1"); shift; done; shift
    tm new-session -d -s "$s" -x 80 -y 25 \
        "$(printf '%q ' /usr/bin/python3 "$FILTER" --answers dsr,cpr,da1,caps "${f[@]}" -- "$BIN" --colors truecolor assets/sphere.obj --background 0,0,0 "$@"); sleep 60"
    wait_for 15 hud_has "$s" " fps" && still_after "$s" 0 || { echo "$s: $(status_line "$s")"; return 1; }
    picture "$s" "$name" > /dev/null
}
bbox_ratio() { # width / height of the non-black pixels of $OUT/NAME.ppm
    python3 - "$OUT/$1.ppm" <<'EOF2'
import sys
b = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, b[1].split()); px = b[3]
xs, ys = [], []
for i in range(w * h):
    if px[3 * i:3 * i + 3] != b"\0\0\0":
        xs.append(i % w); ys.append(i // w)
print("%.3f" % ((max(xs) - min(xs) + 1) / (max(ys) - min(ys) + 1)))
EOF2
}
cell_aspect() {
    aspect_picture a1 two -- || return 1
    aspect_picture a2 flag -- --cell-aspect 2.2 || return 1
    aspect_picture a3 answer --cell 22x10 --pixels 0x0 -- || return 1 # (tmux tells 16x32 px)
    aspect_picture a4 winsize --pixels 800x550 -- || return 1   # 25 rows of 22 px
    aspect_picture a5 wins --cell 11x10 --pixels 800x550 -- || return 1 # TIOCGWINSZ first
    local r2 r22; r2=$(bbox_ratio two); r22=$(bbox_ratio flag)
    echo "sphere's width / height in pixels: 1:2 cells $r2, --cell-aspect 2.2 $r22"
    same_picture two flag && { echo "--cell-aspect 2.2 drew the 1:2 picture"; return 1; }
    same_picture answer flag || { echo "ESC[16t's 22x10 did not draw --cell-aspect 2.2's picture"; return 1; }
    same_picture winsize flag || { echo "TIOCGWINSZ's 800x550 did not draw --cell-aspect 2.2's picture"; return 1; }
    same_picture wins flag || { echo "TIOCGWINSZ did not come before ESC[16t"; return 1; }
    awk -v a="$r2" -v b="$r22" 'BEGIN { exit !(a > 0.95 && a < 1.05 && b > 1.05 && b < 1.15) }'
}
if have_tmux; then check cell_aspect_from_the_terminal_or_the_flag_keeps_circles_round cell_aspect
else skip cell_aspect_from_the_terminal_or_the_flag_keeps_circles_round "tmux not installed"; fi

finish
