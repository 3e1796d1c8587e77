#!/usr/bin/env bash
# glyphs.sh (issue 9): --glyphs in dump and ansi2ppm for every glyph set, and monochrome.
#   - each set decodes at its sub-cell grid (quadrant 2 cols x 2 rows per cell, ...), and the
#     model covers the same share of the picture in every set (the projection uses the
#     cells' physical aspect, not the pixel count)
#   - a bad --glyphs is a one-line error, exit 2
#   - --colors none, NO_COLOR, TERM=dumb: the textured head (dark, in front of a bright sky)
#     stays visible: its silhouette recovered from the decoded monochrome output matches the
#     colour render's (tests/e2e/lib/silhouette.c)
source "$(dirname "$0")/lib/common.sh"

CUBE=assets/cube.obj
HEAD=$SHARED/african_head/african_head.obj
SETS="half quadrant sextant braille ascii"
SIL=build/e2e/silhouette
if [ ! -x $SIL ] || [ tests/e2e/lib/silhouette.c -nt $SIL ]; then
    mkdir -p build/e2e && cc -O2 -std=c11 -o $SIL.$$ tests/e2e/lib/silhouette.c && mv -f $SIL.$$ $SIL
fi

# grid G: pixels per cell, "W H"
grid() { case $1 in half) echo 1 2;; quadrant) echo 2 2;; sextant) echo 2 3;; braille) echo 2 4;; ascii) echo 1 1;; esac; }

every_set() {
    local g share first=
    for g in $SETS; do
        "$BIN" dump $CUBE --frame --cols 40 --rows 12 --glyphs $g --colors truecolor --out $OUT/c-$g.ans || return 1
        "$BIN" ansi2ppm $OUT/c-$g.ans --glyphs $g --out $OUT/c-$g.ppm || return 1
        set -- $(grid $g) $(ppmstat $OUT/c-$g.ppm)
        echo "$g: ${3}x$4, model $5 px"
        [ "$3" = $((40 * $1)) ] && [ "$4" = $((12 * $2)) ] || { echo "expected $((40 * $1))x$((12 * $2))"; return 1; }
        # the model's share of the picture, in 1/1000
        share=$(( $5 * 1000 / ($3 * $4) ))
        first=${first:-$share}
        [ $(( share * 100 )) -ge $(( first * 90 )) ] && [ $(( share * 100 )) -le $(( first * 110 )) ] ||
            { echo "$g: the model covers $share/1000, half blocks $first/1000"; return 1; }
        # without --glyphs, ansi2ppm finds the grid the glyphs drawn need: no finer than the
        # set's (a flat cube may need less), at least half blocks' 1x2
        "$BIN" ansi2ppm $OUT/c-$g.ans --out $OUT/auto-$g.ppm || return 1
        set -- $(grid $g) $(ppmstat $OUT/auto-$g.ppm)
        echo "  auto: ${3}x$4"
        [ $g = ascii ] || { [ $(( 40 * $1 % $3 )) = 0 ] && [ $(( 12 * $2 % $4 )) = 0 ]; } ||
            { echo "auto grid ${3}x$4"; return 1; }
    done
}
check every_glyph_set_decodes_at_its_grid every_set

bad_value() {
    local err rc
    err=$("$BIN" dump $CUBE --glyphs hex --cols 20 --rows 5 2>&1 </dev/null); rc=$?
    echo "exit $rc: $err"
    [ $rc = 2 ] && [ "$(echo "$err" | wc -l)" = 1 ] && echo "$err" | grep -q -- "--glyphs.*hex" || return 1
    err=$("$BIN" ansi2ppm $OUT/c-half.ans --glyphs 7 --out $OUT/x.ppm 2>&1); rc=$?
    echo "exit $rc: $err"
    [ $rc = 2 ] && [ "$(echo "$err" | wc -l)" = 1 ]
}
check bad_glyphs_is_a_one_line_error bad_value

if [ ! -f "$HEAD" ]; then
    skip monochrome_head_keeps_its_silhouette "no shared models at $SHARED"
    skip no_color_and_dumb_terminal_are_monochrome "no shared models at $SHARED"
    finish
fi

# sil_ok G MONO.ppm: the head's silhouette in MONO (decoded on G's grid) against the colour
# render's on a black background; at most 3% wrong beyond a pixel of the outline, 12% in all
sil_ok() {
    "$BIN" dump "$HEAD" --cols 80 --rows 48 --glyphs $1 --colors truecolor --out $OUT/ref-$1.ans &&
        "$BIN" ansi2ppm $OUT/ref-$1.ans --glyphs $1 --out $OUT/ref-$1.ppm || return 1
    local s; s=$($SIL "$2" $OUT/ref-$1.ppm) || return 1
    echo "$1: $s"
    set -- $s
    [ "${4%.*}" -lt 3 ] && [ "${2%.*}" -lt 12 ]
}
mono() {
    local g
    for g in $SETS; do
        "$BIN" dump "$HEAD" --cols 80 --rows 48 --glyphs $g --colors none --sky procedural \
            --out $OUT/m-$g.ans || return 1
        grep -q $'\e\\[[0-9;]*[34]8;' $OUT/m-$g.ans && { echo "$g: colour SGR in none mode"; return 1; }
        "$BIN" ansi2ppm $OUT/m-$g.ans --glyphs $g --out $OUT/m-$g.ppm || return 1
        if [ $g != ascii ]; then # the head uses every pattern: the auto grid is the set's
            "$BIN" ansi2ppm $OUT/m-$g.ans --out $OUT/auto.ppm && cmp $OUT/auto.ppm $OUT/m-$g.ppm || return 1
        fi
        sil_ok $g $OUT/m-$g.ppm || return 1
    done
}
check monochrome_head_keeps_its_silhouette mono

# NO_COLOR and TERM=dumb pick monochrome for a terminal: dump straight to a tmux pane
env_mono() {
    have_tmux || { echo "no tmux"; return 0; }
    local name env
    for env in NO_COLOR=1 TERM=dumb; do
        name=m${env%%=*}
        tm new-session -d -s $name -x 80 -y 49 "env -u COLORTERM TERM=xterm-256color $env $(printf '%q ' "$BIN") dump $(printf '%q' "$HEAD") --cols 80 --rows 48 --glyphs quadrant --sky procedural; touch $OUT/$name.done; sleep 30"
        wait_for 20 test -f $OUT/$name.done && output_done $name || return 1
        tm capture-pane -t $name -p | grep -q '[▘▝▀▖▌▞▛▗▚▐▜▄▙▟]' || { echo "$env: no quadrant glyphs on the screen"; return 1; }
        tm capture-pane -t $name -e -N -p | head -n 48 > $OUT/$name.ans
        tm kill-session -t $name
        "$BIN" ansi2ppm $OUT/$name.ans --glyphs quadrant --out $OUT/$name.ppm || return 1
        echo "$env:"; sil_ok quadrant $OUT/$name.ppm || return 1
    done
}
check no_color_and_dumb_terminal_are_monochrome env_mono

finish
