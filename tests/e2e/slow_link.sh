#!/usr/bin/env bash
# slow_link.sh (issue 11): the viewer behind a slow link — ../shared/tools/slowlink.py, a pty
# whose output leaves at RATE bytes/s through a deep queue, like ssh over a slow line.
#   - key -> screen latency with the textured head spinning in truecolor, at 1 Mbit/s in
#     160x48 and 4 Mbit/s in 320x90 (tests/e2e/lib/keylat.py presses f and times the status
#     line): generous bounds here, the tight numbers are `make bench`'s
#   - Ctrl-Z or q with a frame in flight: the status report's answer must not reach the shell
#   - the quality floor (issue 25 item 3): at 256 kbit/s every frame written decodes within
#     30 dB of its picture; the demo's own spin pauses and says so; a key's status line goes
#     out at once, not with the next frame (these need only tmux)
source "$(dirname "$0")/lib/common.sh"

LINK=${RASTTY_SHARED:-../shared}/tools/slowlink.py
HEAD=$SHARED/african_head
NAMES=(key_to_screen_at_1_mbit_160x48 key_to_screen_at_4_mbit_320x90
       ctrl_z_and_q_with_a_frame_in_flight_leak_nothing)
FLOOR=(every_frame_at_256_kbit_is_within_30_db_demo_pauses_its_spin
       every_frame_at_256_kbit_is_within_30_db_with_spin
       a_keys_status_line_goes_out_before_the_next_frame)
if ! have_tmux; then
    for n in "${NAMES[@]}" "${FLOOR[@]}"; do skip "$n" "tmux not installed"; done
    finish
fi

# The quality floor (include/viewer/view_frames.h). --bandwidth 32000 (256 kbit/s) paces
# the viewer itself, with no real link: the machine's load changes how many frames go out,
# never what each one is. The viewer decodes every frame it writes and logs its PSNR against
# the framebuffer it came from (RASTTY_FRAME_LOG); each must be >= 30 dB. Before the floor:
# 15-21 dB ghosts (flat sky, doubled objects) while the demo spun.
# floor_frames SESSION COLSxROWS FRAMES ARGS...: wait for FRAMES frames, then judge them all
log_frames() { [ "$(grep -c '^frame ' "$1" 2>/dev/null)" -ge "$2" ]; }
floor_frames() {
    local s=$1 size=$2 want=$3; shift 3
    local log=$OUT/$s.log
    rm -f "$log"
    tm new-session -d -s "$s" -x "${size%x*}" -y "${size#*x}" \
        "RASTTY_FRAME_LOG=$PWD/$log $(printf '%q ' "$BIN" --colors truecolor --bandwidth 32000 "$@"); sleep 120"
    wait_for 60 log_frames "$log" "$want" || { echo "fewer than $want frames:"; cat "$log"; return 1; }
    awk '$1 == "frame" && $12 != "inf" && ($12 == "?" || $12 + 0 < 30) { bad = 1; print "below 30 dB: " $0 }
         END { exit bad }' "$log" || return 1
    echo "$(grep -c '^frame ' "$log") frames, PSNR $(awk '$1 == "frame" { printf " %s", $12 }' "$log")"
}
demo_floor() {
    floor_frames floor_demo 160x30 1 || return 1
    # the demo's own spin could not be carried whole: paused, and the status line says so
    wait_for 30 hud_has floor_demo "spin paused" ||
        { echo "spin not paused: $(status_line floor_demo)"; return 1; }
    tm kill-session -t floor_demo
}
spin_floor() { floor_frames floor_spin 80x24 4 --spin && tm kill-session -t floor_spin; }
check every_frame_at_256_kbit_is_within_30_db_demo_pauses_its_spin demo_floor
check every_frame_at_256_kbit_is_within_30_db_with_spin spin_floor

# A key's status line goes out at once, behind the frame on its way, not with the next frame
# (which waits for the link: here --bandwidth 8000, a frame of the spinning demo takes
# seconds). The log (RASTTY_FRAME_LOG) says when each key was read and how its status line
# went: "hud ... bytes N" right after the key is a write of its own. Three presses of f, each
# waited for on the status line; a press landing just as a frame may go out rides with it,
# so at least one of the three must have gone alone (before: none ever did).
status_at_once() {
    local s=hud_now log=$OUT/hud_now.log f
    rm -f "$log"
    tm new-session -d -s $s -x 80 -y 24 \
        "RASTTY_FRAME_LOG=$PWD/$log $(printf '%q ' "$BIN" --colors truecolor --bandwidth 8000 --spin); sleep 120"
    wait_for 60 log_frames "$log" 2 || { echo "no second frame:"; cat "$log"; return 1; }
    for f in nearest bilinear trilinear; do
        tm send-keys -t $s f
        wait_for 30 hud_has $s " $f " || { echo "status line lacks $f: $(status_line $s)"; return 1; }
    done
    tm kill-session -t $s
    local alone
    alone=$(awk '$1 == "key" { k = 1; next } k && $1 == "hud" { n += NF > 3; k = 0 } k && $1 == "frame" { k = 0 }
                 END { print n + 0 }' "$log")
    echo "$alone of 3 status lines went out alone"
    [ "$alone" -ge 1 ] || { grep -v '^frame' "$log"; return 1; }
}
check a_keys_status_line_goes_out_before_the_next_frame status_at_once
if [ ! -f "$LINK" ] || [ ! -f "$HEAD/african_head.obj" ]; then
    for n in "${NAMES[@]}"; do skip "$n" "no $LINK or shared african_head (../shared absent)"; done
    finish
fi

prompt_shown() { tm capture-pane -t "$1" -p | grep -qE '[#$] ?$'; }

# latency RATE SIZE MEDIAN_MS WORST_MS: median and worst key -> screen within the bounds
latency() {
    local rate=$1 size=$2 med_max=$(( $3 * SLOW )) worst_max=$(( $4 * SLOW ))
    local out
    out=$(/usr/bin/python3 tests/e2e/lib/keylat.py --socket "$SOCK-lat" --rate "$rate" \
          --queue 1000000 --size "$size" --presses 8 --warmup 2 --slowlink "$LINK" -- \
          "$BIN" --colors truecolor --spin "$HEAD/african_head.obj") || { echo "$out"; return 1; }
    echo "$out" | tail -n 1
    set -- $(echo "$out" | tail -n 1 | sed -E 's/.*median ([0-9]+) worst ([0-9]+).*/\1 \2/')
    [ "$1" -le "$med_max" ] && [ "$2" -le "$worst_max" ] ||
        { echo "want median <= $med_max ms, worst <= $worst_max ms"; return 1; }
}
# the issue's targets are 300 / 800 ms; today's numbers are in make bench
check key_to_screen_at_1_mbit_160x48 latency 128000 160x48 1000 2500
check key_to_screen_at_4_mbit_320x90 latency 512000 320x90 1000 2500

# A shell behind a 20 KB/s link; the viewer spins in it (a frame is nearly always on its way
# and its DSR answer with it); Ctrl-Z, then `fg`: the shell must read exactly "fg"; then q:
# nothing after the viewer either.
ctrl_z() {
    local s=cz
    tm new-session -d -s $s -x 100 -y 30 "/usr/bin/python3 $LINK 20000 200000 -- bash --norc --noprofile"
    wait_for 10 prompt_shown $s || { echo "no shell prompt"; return 1; }
    tm send-keys -t $s "$(printf '%q ' "$BIN" --colors truecolor --spin "$HEAD/african_head.obj")" Enter
    wait_for 30 hud_has $s " fps" || { echo "viewer did not start"; return 1; }
    sleep 1
    tm send-keys -t $s C-z
    wait_for 20 sh -c "tmux -L $SOCK capture-pane -t $s -p | grep -q Stopped" || { echo "not stopped"; return 1; }
    sleep 1                                     # anything still on its way arrives now
    tm send-keys -t $s "fg" Enter
    wait_for 30 hud_has $s " fps" || { echo "fg did not bring it back:"; tm capture-pane -t $s -p | grep -v '^$' | tail -4; return 1; }
    tm send-keys -t $s q
    wait_for 20 sh -c "tmux -L $SOCK capture-pane -t $s -p | grep -q 'fg$'" || true
    local text; text=$(tm capture-pane -t $s -p -S - | grep -v '^$')
    if echo "$text" | grep -qE '0n|nfg|\^\['; then echo "the answer reached the shell:"; echo "$text" | tail -5; return 1; fi
}
check ctrl_z_and_q_with_a_frame_in_flight_leak_nothing ctrl_z

finish
