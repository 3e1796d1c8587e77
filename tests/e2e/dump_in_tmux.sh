#!/usr/bin/env bash
# dump_in_tmux.sh (issue 3): what `rastty dump` puts on a real terminal (tmux) decodes back to
# exactly the framebuffer it rendered, for a single frame and for a `cat`-replayed diff stream.
source "$(dirname "$0")/lib/common.sh"

if [ -f "$SHARED/african_head/african_head.obj" ]; then
    MODEL=("$SHARED/african_head/african_head.obj" --texture "$SHARED/african_head/african_head_diffuse.tga")
else
    MODEL=(assets/teapot.obj --frame)
fi

if ! have_tmux; then
    skip dump_on_terminal_decodes_to_framebuffer "tmux not installed"
    skip cat_replay_of_diff_stream_ends_on_last_frame "tmux not installed"
    finish
fi

# 1. dump straight onto the terminal: stdout is the pane, so the size is the pane's (100x30)
single() {
    mkdir -p "$OUT/single"
    tm new-session -d -s d1 -x 100 -y 30 \
        "$(printf '%q ' "$BIN" dump "${MODEL[@]}" --colors truecolor --ppm-dir "$OUT/single"); touch $OUT/single/done; sleep 60"
    wait_for 20 test -f "$OUT/single/done" || return 1
    output_done d1 || return 1
    capture d1 "$OUT/single/screen.ans"
    decode "$OUT/single/screen.ans" "$OUT/single/screen.ppm" || return 1
    local want=$OUT/single/frame-0000.ppm
    echo "framebuffer: $(ppmstat "$want")"
    echo "decoded:     $(ppmstat "$OUT/single/screen.ppm")"
    cmp "$want" "$OUT/single/screen.ppm"
}
check dump_on_terminal_decodes_to_framebuffer single

# 2. a diff stream written to a file, replayed with cat: the screen ends on the last frame
replay() {
    mkdir -p "$OUT/replay"
    "$BIN" dump "${MODEL[@]}" --cols 100 --rows 30 --colors truecolor --frames 12 --orbit 7 \
        --diff --out "$OUT/replay/spin.ans" --ppm-dir "$OUT/replay" || return 1
    tm new-session -d -s d2 -x 100 -y 30 "cat $OUT/replay/spin.ans; touch $OUT/replay/done; sleep 60"
    wait_for 20 test -f "$OUT/replay/done" || return 1
    output_done d2 || return 1
    capture d2 "$OUT/replay/screen.ans"
    decode "$OUT/replay/screen.ans" "$OUT/replay/screen.ppm" || return 1
    cmp "$OUT/replay/frame-0011.ppm" "$OUT/replay/screen.ppm" || return 1
    # and the file itself decodes to every frame
    for k in 0 5 11; do
        "$BIN" ansi2ppm "$OUT/replay/spin.ans" --frame $k --out "$OUT/replay/dec$k.ppm" &&
            cmp "$OUT/replay/dec$k.ppm" "$(printf '%s/frame-%04d.ppm' "$OUT/replay" $k)" || return 1
    done
}
check cat_replay_of_diff_stream_ends_on_last_frame replay

# 3. output to a pipe: no terminal set-up codes, default 80x24, starts at home
pipe_defaults() {
    "$BIN" dump assets/cube.obj --frame --colors truecolor > "$OUT/pipe.ans" || return 1
    head -c 3 "$OUT/pipe.ans" | od -c | head -1 | grep -q '033   \[   H' || { echo "does not start with ESC[H"; return 1; }
    if grep -qa $'\e\[?1049\|\e\[?25l' "$OUT/pipe.ans"; then echo "terminal set-up codes in a pipe"; return 1; fi
    "$BIN" ansi2ppm "$OUT/pipe.ans" --out "$OUT/pipe.ppm" || return 1
    set -- $(ppmstat "$OUT/pipe.ppm")
    [ "$1x$2" = 80x48 ] || { echo "size $1x$2, want 80x48"; return 1; }
}
check dump_to_pipe_is_80x24_without_setup_codes pipe_defaults

finish
