#!/usr/bin/env bash
# viewer.sh (issue 4): the real viewer in a detached tmux: demo scene, camera keys move the
# picture the expected way, resize refills the window, idle writes nothing, and every way
# out (q, Esc, Ctrl-C, SIGTERM, SIGHUP) leaves the shell with echo and canonical mode on.
source "$(dirname "$0")/lib/common.sh"

NAMES=(suspend_and_resume_repaints demo_scene_starts_and_fills_window zoom_in_grows_the_model strafe_right_moves_model_left mouse_wheel_zooms_and_drag_orbits
       fly_yaw_left_moves_model_right tap_moves_the_same_after_idle resize_refills_the_window idle_viewer_writes_nothing
       tiny_and_huge_terminals quit_restores_terminal sigterm_on_a_stalled_terminal
       stopped_continued_viewer_ends_on_sigterm hung_up_terminal_ends_the_viewer
       help_overlay_drawn_once_and_closed_by_q status_line_at_80_columns spin_rules
       status_line_names_the_texture a_models_warning_shows_on_the_status_line
       no_alt_screen_terminal_is_cleared_at_exit no_hud_viewer_idles_and_ends_with_its_terminal
       an_outside_stop_and_continue_leaves_the_prompt_alone a_1000x300_terminal_draws_its_frame_and_idles
       the_viewer_runs_on_a_64k_stack
       screenshot_key_writes_png_ans_and_a_command_that_reproduces_it)
if ! have_tmux; then
    for n in "${NAMES[@]}"; do skip "$n" "tmux not installed"; done
    finish
fi

# start the viewer in session $1 (cols $2 rows $3) with arguments; wait for its status line
# (a model stands still after that: still_after S 0 waits for its first whole picture)
start() {
    local s=$1 c=$2 r=$3; shift 3
    tm new-session -d -s "$s" -x "$c" -y "$r" \
        "$(printf '%q ' "$BIN" --colors truecolor "$@"); echo EXIT=\$? > $OUT/$s.exit; sleep 120"
    wait_for 15 hud_has "$s" " fps" || { echo "no status line"; tm capture-pane -t "$s" -p | tail -3; return 1; }
}
# the picture of session $1 (status line dropped) as $OUT/$2.ppm; echo its stats
picture() {
    local rows; rows=$(tm display -p -t "$1" '#{pane_height}')
    capture "$1" "$OUT/$2.ans" $((rows - 1))
    decode "$OUT/$2.ans" "$OUT/$2.ppm" && ppmstat "$OUT/$2.ppm" "${3:-0,0,0}"
}
# the picture's rows of session $1 (status line dropped, colours kept), for comparing
screen() {
    local o; o=$(tm capture-pane -t "$1" -e -p; echo .)
    o=${o%.}; o=${o%$'\n'}; printf '%s' "${o%$'\n'*}"
}
# wait until session $1's picture differs from $2 (a screen())
changes() { wait_for 5 screen_differs "$1" "$2"; }
screen_differs() { [ "$(screen "$1")" != "$2" ]; }
# mouse report bytes (send-keys -H) that move the camera, then the still picture they lead to
mouse_keys() {
    local s=$1 n; shift
    n=$(frame_no "$s"); tm send-keys -t "$s" -H "$@"; still_after "$s" "$n"
}
# Everything sent to session $1 so far has been taken and drawn, also input that draws
# nothing or several frames: `i` (the camera on the status line) goes in after it, and a
# still picture whose status line has the camera field turned over came after all of it.
# Needs a status line wide enough for the camera field.
barrier() {
    local s=$1 want=shown
    hud_has "$s" "| eye " && want=gone
    tm send-keys -t "$s" i
    wait_for 10 camera_field "$s" $want || { echo "barrier: $(status_line "$s")"; return 1; }
}
camera_field() { # S shown|gone: on a still picture's status line
    local l; l=$(status_line "$1")
    [[ $l =~ \ \#[0-9]+ ]] || return 1
    if [ "$2" = shown ]; then [[ $l == *"| eye "* ]]; else [[ $l != *"| eye "* ]]; fi
}

demo() {
    start demo 100 30 || return 1
    tm capture-pane -t demo -p | tail -n 1 | grep -q "demo.rsc" || { echo "status line lacks demo.rsc"; return 1; }
    keys demo Space || return 1
    set -- $(picture demo demo)
    echo "demo picture: $*"
    [ "$1x$2" = 100x58 ] || { echo "size $1x$2, want 100x58"; return 1; }
    [ "$6" -gt 200 ] || { echo "only $6 colours"; return 1; }
    [ "$3" -eq 5800 ] || { echo "$((5800 - $3)) black pixels: the sky should fill the window"; return 1; }
}
check demo_scene_starts_and_fills_window demo

# a lone model on black: area and centroid tell where the camera went
model_session() { start m 80 25 assets/sphere.obj --background 0,0,0 && still_after m 0; }
zoom() {
    model_session || return 1
    set -- $(picture m before); local a0=$3
    keys m w w w || return 1
    set -- $(picture m after); local a1=$3
    echo "area before $a0, after zoom $a1"
    [ "$a1" -gt $((a0 * 5 / 4)) ]
}
check zoom_in_grows_the_model zoom

strafe() {
    keys m r || return 1
    set -- $(picture m s0); local x0=$4
    keys m d d || return 1
    set -- $(picture m s1); local x1=$4
    echo "centroid x before $x0, after 'd' $x1"
    awk -v a="$x0" -v b="$x1" 'BEGIN { exit !(b < a - 2) }'
}
check strafe_right_moves_model_left strafe

# R cycles the rasterizer without changing a byte of the picture; p and Z cycle the
# interpolation and depth methods; the status line names each
method_keys() {
    start k 100 25 assets/teapot.obj --texture assets/checker.png --background 0,0,0 || return 1
    still_after k 0 || return 1
    picture k r0 >/dev/null
    local want; want=$(md5sum < "$OUT/r0.ans")
    for r in scanline tiled; do
        keys k R || return 1
        said "$r" || { echo "status line lacks $r: $LAST_STATUS"; return 1; }
        picture k "r_$r" >/dev/null
        [ "$(md5sum < "$OUT/r_$r.ans")" = "$want" ] || { echo "--raster $r changed the picture"; return 1; }
    done
    keys k p || return 1
    said "interpolation: affine" || { echo "p: no affine: $LAST_STATUS"; return 1; }
    picture k affine >/dev/null
    [ "$(md5sum < "$OUT/affine.ans")" != "$want" ] || { echo "affine drew the same picture"; return 1; }
    keys k Z || return 1
    said "depth buffer: w" || { echo "Z: no w: $LAST_STATUS"; return 1; }
}
check method_keys_cycle_and_rasterizers_agree method_keys

# mouse: the wheel zooms and a left drag orbits, from SGR reports (?1006, which the viewer
# asks for: they work past column 223) and from X10 reports (terminals without 1006)
mouse() {
    local s=wide
    start $s 260 30 assets/cube.obj --background 0,0,0 || return 1
    still_after $s 0 || return 1
    set -- $(picture $s m0); local a0=$3 x0=$4
    mouse_keys $s 1b 5b 3c 36 34 3b 32 35 30 3b 31 35 4d || return 1           # ESC[<64;250;15M wheel up
    set -- $(picture $s m1); local a1=$3
    echo "SGR wheel up at column 250: area $a0 -> $a1"
    [ "$a1" -gt $((a0 * 11 / 10)) ] || return 1
    mouse_keys $s 1b 5b 4d 61 3a 2f || return 1                                # ESC[M a : / X10 wheel down at 26,15
    set -- $(picture $s m2); local a2=$3
    echo "X10 wheel down: area $a1 -> $a2"
    [ "$a2" -lt $((a1 * 10 / 11)) ] || return 1
    # drag from column 230 to 250 (press, two motions, release), all past column 223
    tm send-keys -t $s -H 1b 5b 3c 30 3b 32 33 30 3b 31 35 4d                  # ESC[<0;230;15M
    tm send-keys -t $s -H 1b 5b 3c 33 32 3b 32 34 30 3b 31 35 4d               # ESC[<32;240;15M
    tm send-keys -t $s -H 1b 5b 3c 33 32 3b 32 35 30 3b 31 35 4d               # ESC[<32;250;15M
    tm send-keys -t $s -H 1b 5b 3c 30 3b 32 35 30 3b 31 35 6d                  # ESC[<0;250;15m
    barrier $s || return 1
    set -- $(picture $s m3); local x3=$4
    echo "after a 20-column drag: $(cmp -l $OUT/m2.ppm $OUT/m3.ppm | wc -l) bytes differ; centroid x $x0 -> $x3"
    ! cmp -s $OUT/m2.ppm $OUT/m3.ppm || { echo "the drag did not orbit"; return 1; }
    # an orbit turns the cube about its centre: it stays in the middle of the window
    awk -v a="$x0" -v b="$x3" 'BEGIN { d = a - b; exit !(d < 8 && d > -8) }' || { echo "the model moved off centre"; return 1; }
    # a motion report with no button pressed before it does nothing
    tm send-keys -t $s -H 1b 5b 3c 33 32 3b 31 30 3b 31 30 4d                  # ESC[<32;10;10M
    barrier $s || return 1
    picture $s m4 >/dev/null
    cmp -s $OUT/m3.ppm $OUT/m4.ppm || { echo "motion without a press moved the camera"; return 1; }
    # malformed or foreign reports (huge numbers, missing fields, other buttons) are ignored
    local r
    for r in '<99999999999999999999;1;1M' '<0;0;0M' '<;;M' '<0;5M' '<64;10;10m' '<2;5;5M' \
             '<0;5;5;7M' '<-1;5;5M' '<32;999;999M'; do
        tm send-keys -t $s -l $'\e['"$r"
    done
    barrier $s || return 1
    picture $s m5 >/dev/null
    cmp -s $OUT/m4.ppm $OUT/m5.ppm || { echo "a malformed report moved the camera"; return 1; }
    hud_has $s " fps" || { echo "the viewer is gone after malformed reports"; return 1; }
    tm kill-session -t $s
}
check mouse_wheel_zooms_and_drag_orbits mouse

fly_yaw() {
    keys m r o || return 1          # o: fly mode
    tm capture-pane -t m -p | tail -n 1 | grep -qE "\| fly( |$)" || { echo "status line does not say fly"; return 1; }
    set -- $(picture m y0); local x0=$4
    keys m Left || return 1
    set -- $(picture m y1); local x1=$4
    echo "centroid x before $x0, after Left (turn left) $x1"
    awk -v a="$x0" -v b="$x1" 'BEGIN { exit !(b > a + 2) }'
}
check fly_yaw_left_moves_model_right fly_yaw

# a tap turns by the same angle however long the viewer sat idle before it (time is
# counted from the key press, not from the last frame)
tap_after_idle() {
    local idle x=()
    for idle in 0.2 3; do
        keys m r || return 1
        sleep "$idle"
        keys m Left || return 1
        set -- $(picture m tap-$idle); x+=("$4")
    done
    echo "centroid x after a tap: ${x[0]} (idle 0.2 s), ${x[1]} (idle 3 s)"
    awk -v a="${x[0]}" -v b="${x[1]}" 'BEGIN { d = a - b; exit !(a > 41 && d < 1 && d > -1) }'
}
check tap_moves_the_same_after_idle tap_after_idle

resize() {
    local n; n=$(frame_no demo)        # the demo stands still (Space)
    tm resize-window -t demo -x 70 -y 20
    still_after demo "$n" || return 1
    set -- $(picture demo resized)
    echo "after resize to 70x20: $*"
    [ "$1x$2" = 70x38 ] || return 1
    [ "$3" -eq $((70 * 38)) ] || { echo "unfilled pixels"; return 1; }
    tm capture-pane -t demo -p | tail -n 1 | grep -q "demo.rsc"
}
check resize_refills_the_window resize

idle() {
    local log=$OUT/pane.log
    : > "$log"
    tm pipe-pane -o -t m "cat >> $log"
    keys m Left Left Left || return 1                    # move a while, then nothing
    local n; n=$(frame_no m)
    wait_for 5 log_ends_with_frame "$log" "$n" || { echo "frame #$n is not all in the log"; return 1; }
    local s0 s1 s2
    s0=$(stat -c %s "$log"); sleep 1; s1=$(stat -c %s "$log")
    echo "bytes written while idle for 1 s: $((s1 - s0))"
    [ "$s1" -eq "$s0" ] || return 1
    keys m w || return 1
    wait_for 5 log_ends_with_frame "$log" "$(frame_no m)"
    s2=$(stat -c %s "$log")
    echo "bytes after a key: $((s2 - s1))"
    [ "$s2" -gt "$s1" ]
}
check idle_viewer_writes_nothing idle

extremes() {
    tm new-session -d -s tiny -x 10 -y 3 "$(printf '%q ' "$BIN" --colors truecolor); echo EXIT=\$? > $OUT/tiny.exit; sleep 60"
    wait_for 15 hud_has tiny " demo" || { echo "no status line at 10x3: $(status_line tiny)"; return 1; }
    tm send-keys -t tiny q
    wait_for 10 test -s "$OUT/tiny.exit" || return 1
    grep -q EXIT=0 "$OUT/tiny.exit" || { cat "$OUT/tiny.exit"; return 1; }
    start huge 300 100 || return 1
    keys huge Space || return 1
    set -- $(picture huge huge)
    echo "300x100 terminal: $*"
    [ "$1x$2" = 300x198 ] && [ "$3" -eq $((300 * 198)) ]
}
check tiny_and_huge_terminals extremes

# Ctrl-Z gives the shell a sane terminal; fg takes it back and repaints at once
suspend_resume() {
    local s=z$RANDOM f=$OUT/stty-suspended.txt
    tm new-session -d -s $s -x 80 -y 24 bash --norc --noprofile
    tm send-keys -t $s "$(printf '%q ' "$BIN" --colors truecolor --background 40,40,40 assets/sphere.obj)" Enter
    wait_for 15 hud_has $s " fps" || { echo "viewer did not start"; return 1; }
    still_after $s 0 || return 1
    local n; n=$(frame_no $s)
    tm send-keys -t $s C-z
    wait_for 10 sh -c "tmux -L $SOCK capture-pane -t $s -p | grep -q Stopped" || { echo "not stopped"; return 1; }
    tm send-keys -t $s "stty -a > $f" Enter
    wait_for 10 test -s $f || return 1
    grep -qE '(^| )icanon( |$)' $f && grep -qE '(^| )echo( |$)' $f || { echo "suspended with a raw terminal"; return 1; }
    tm send-keys -t $s "clear; fg" Enter
    still_after $s "$n" || { echo "no repaint after fg"; return 1; }
    set -- $(picture $s resumed 40,40,40)
    echo "after fg: $*"
    [ "$1x$2" = 80x46 ] && [ "$3" -gt 200 ] || { echo "not repainted"; return 1; }
    tm send-keys -t $s q
}
check suspend_and_resume_repaints suspend_resume

# every way out (a crash signal included): run under a non-interactive sh (which, unlike an interactive bash, does not
# repair the terminal after its child dies), then ask for the terminal modes
quit_ways() {
    local how rc=0
    for how in q Escape EscDSR C-c TERM HUP SEGV KILL; do
        local s=q$RANDOM f=$OUT/stty-$how.txt tag=$OUT/quit-$how-$$.rsc
        echo "model $PWD/assets/cube.obj" > "$tag"   # a unique name to find the process by
        tm new-session -d -s $s -x 80 -y 24 \
            "sh -c 'trap \"\" INT; $(printf '%q ' "$BIN" --colors truecolor "$tag") 2>/dev/null; echo \$? > $f.rc; stty -a > $f; sleep 60'"
        wait_for 15 hud_has $s " fps" || { echo "$how: viewer did not start"; rc=1; continue; }
        case $how in
            TERM|HUP|SEGV|KILL) pkill -$how -f -- "^$BIN .*$tag" ;;   # rastty, not the sh around it
            # Esc with a DSR answer ("ESC [ 0 n") right behind it, inside the escape delay: what
            # a slow link delivers while a frame is in flight; the Esc must not be swallowed
            EscDSR) tm send-keys -t $s -H 1b 1b 5b 30 6e ;;
            *) tm send-keys -t $s $how ;;
        esac
        wait_for 10 test -s "$f" || { echo "$how: no terminal modes recorded"; rc=1; continue; }
        local broken=0
        if grep -qE '(^| )-echo( |$)|(^| )-icanon( |$)' "$f" || ! grep -qE '(^| )echo( |$)' "$f" || ! grep -qE '(^| )icanon( |$)' "$f"; then
            broken=1
        fi
        # what the terminal still does: mouse reports (any mode, SGR), alternate screen,
        # cursor shown — tmux keeps these per pane; restored = "0 0 0 1"
        local modes; modes=$(tm display -p -t $s '#{mouse_any_flag} #{mouse_sgr_flag} #{alternate_on} #{cursor_flag}')
        [ "$modes" = "0 0 0 1" ] || broken=1
        if [ $how = KILL ]; then
            # nothing can restore after SIGKILL: this proves the check sees a broken terminal
            [ $broken = 1 ] || { echo "KILL: the check did not notice the unrestored terminal"; rc=1; }
        elif [ $broken = 1 ]; then
            echo "$how: terminal modes not restored (mouse any, sgr, alternate screen, cursor: $modes):"
            grep -oE -- '-?(echo|icanon)( |$)' "$f" | tr '\n' ' '; echo; rc=1
        else
            local want_rc
            # SEGV: the crash handler restores the terminal, then dies by the signal (128 + 11)
            case $how in q|Escape|EscDSR) want_rc=0 ;; C-c) want_rc=130 ;; HUP) want_rc=129 ;; TERM) want_rc=143 ;; SEGV) want_rc=139 ;; esac
            if [ "$(cat $f.rc)" != "$want_rc" ]; then   # 134 = abort: a sanitizer report at exit
                echo "$how: exit status $(cat $f.rc), want $want_rc"; rc=1
            fi
            # the alternate screen is gone: no half blocks left on the screen
            if tm capture-pane -t $s -p | grep -q '▀'; then echo "$how: picture still on screen"; rc=1; fi
        fi
        tm kill-session -t $s
    done
    return $rc
}
check quit_restores_terminal quit_ways

# The help overlay is drawn once, not with every frame, and q/Esc close it (not the viewer).
dsr_count() { LC_ALL=C grep -ao $'\e\[5n' "$1" | wc -l; }
dsr_past() { [ "$(dsr_count "$1")" -ge "$2" ]; }
help_overlay() {
    local s=hp log=$OUT/help.log
    start $s 100 40 --spin || return 1          # the demo, spinning: a frame every 1/60 s
    : > $log; tm pipe-pane -o -t $s "cat >> $log"
    tm send-keys -t $s ?
    wait_for 5 grep -aq "shading: wire flat" $log || { echo "no help drawn"; return 1; }
    # 60 more frames of spinning under the help (each frame ends with a DSR request)
    local f0; f0=$(dsr_count $log)
    wait_for 10 dsr_past $log $((f0 + 60)) || { echo "fewer than 60 frames: $(dsr_count $log)"; return 1; }
    local n; n=$(grep -ac "shading: wire flat" $log)
    echo "help text sent $n times in $(( $(dsr_count $log) - f0 )) frames of spinning"
    [ "$n" -eq 1 ] || return 1
    tm capture-pane -t $s -p | grep -q "shading: wire flat" || { echo "help not on screen"; return 1; }
    # q closes the help; Space pauses the spin, and the still picture after it says the viewer
    # took both keys
    tm send-keys -t $s q
    keys $s Space || { echo "q quit the viewer instead of closing the help"; return 1; }
    tm capture-pane -t $s -p | grep -q "shading: wire flat" && { echo "q did not close the help"; return 1; }
    hud_has $s " fps" || { echo "q quit the viewer instead of closing the help"; return 1; }
    keys $s ? || return 1
    tm capture-pane -t $s -p | grep -q "shading: wire flat" || { echo "help not on screen"; return 1; }
    keys $s Escape || { echo "Esc quit the viewer instead of closing the help"; return 1; }
    tm capture-pane -t $s -p | grep -q "shading: wire flat" && { echo "Esc did not close the help"; return 1; }
    hud_has $s " fps" || { echo "Esc quit the viewer instead of closing the help"; return 1; }
    tm send-keys -t $s q
    wait_for 5 test -s $OUT/$s.exit && grep -q EXIT=0 $OUT/$s.exit
}
check help_overlay_drawn_once_and_closed_by_q help_overlay

# At 80 columns the status line still names the model, shading, filter, colour mode and fps.
status80() {
    start s80 80 24 assets/cube.obj || return 1
    local line; line=$(tm capture-pane -t s80 -p | tail -n 1)
    echo "status line: '$line'"
    echo "$line" | grep -qE '^ cube\.obj \[1/1\] \| textured trilinear \| truecolor \| [0-9]+ fps'
}
check status_line_at_80_columns status80

# The status line names the texture in use: the file found beside a model, or "untextured".
texture_named() {
    local d=$OUT/tex; mkdir -p $d
    grep -v '^mtllib\|^usemtl' assets/sphere.obj > $d/ball.obj
    start tx1 200 24 $d/ball.obj || return 1
    hud_has tx1 "| untextured |" || { tm capture-pane -t tx1 -p | tail -n 1; return 1; }
    cp assets/checker.png $d/ball_diffuse.png
    start tx2 200 24 $d/ball.obj || return 1
    hud_has tx2 "| tex:ball_diffuse.png |" || { tm capture-pane -t tx2 -p | tail -n 1; return 1; }
}
check status_line_names_the_texture texture_named

# Auto-rotation: on for the demo, off for a model; --spin turns it on; the first camera key
# stops it; Space starts it again and pauses it (issue 25: it said to quit and use --spin);
# --no-spin keeps the demo still.
spin_rules() {
    local a b
    start sd 80 24 || return 1
    a=$(screen sd)
    changes sd "$a" || { echo "the demo does not spin"; return 1; }
    keys sd Left || { echo "a camera key did not stop the spin (no still picture)"; return 1; }
    a=$(screen sd); sleep 0.5
    b=$(screen sd)
    [ "$a" = "$b" ] || { echo "a camera key did not stop the spin"; return 1; }
    tm send-keys -t sd Space
    changes sd "$a" || { echo "Space did not start the spin a camera key stopped"; return 1; }
    keys sd Space || { echo "Space did not pause the spin (no still picture)"; return 1; }
    a=$(screen sd); sleep 0.5
    b=$(screen sd)
    [ "$a" = "$b" ] || { echo "Space did not pause the spin"; return 1; }
    start sm 80 24 --spin assets/cube.obj || return 1
    a=$(screen sm)
    changes sm "$a" || { echo "--spin does not spin a model"; return 1; }
    start sn 80 24 --no-spin || return 1
    still_after sn 0 || { echo "--no-spin: the demo spins (no still picture)"; return 1; }
    a=$(screen sn); sleep 0.5
    b=$(screen sn)
    [ "$a" = "$b" ] || { echo "--no-spin: the demo spins"; return 1; }
    tm kill-session -t sd; tm kill-session -t sm; tm kill-session -t sn # sm spins on
}
check spin_rules spin_rules

# S writes the frame as PNG and ANSI and, at exit, the render command line; running that
# command writes the same PNG, byte for byte.
screenshot() {
    local d=$OUT/shots bin; mkdir -p $d; bin=$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")
    tm new-session -d -s sh -x 90 -y 30 -c $d \
        "$(printf '%q ' "$bin" --colors truecolor "$PWD/assets/demo.rsc"); sleep 60"
    wait_for 15 hud_has sh " fps" || return 1
    keys sh Left Up i c S || return 1
    wait_for 5 test -s $d/rastty-001.png || { echo "no PNG"; return 1; }
    test -s $d/rastty-001.ans || { echo "no ANSI"; return 1; }
    tm send-keys -t sh q
    wait_for 5 sh -c "tmux -L $SOCK capture-pane -t sh -p -J | grep -q '^screenshot: '"
    local cmd; cmd=$(tm capture-pane -t sh -p -J | grep '^screenshot: ' | sed 's/^screenshot: //')
    echo "printed: $cmd"
    [ -n "$cmd" ] || return 1
    mv $d/rastty-001.png $d/viewer.png
    (cd $d && eval "\"$bin\" ${cmd#rastty }") || return 1
    cmp $d/viewer.png $d/rastty-001.png || return 1
    "$BIN" ansi2ppm $d/rastty-001.ans --out $d/ans.ppm && convert $d/viewer.png $d/png.ppm 2>/dev/null &&
        { cmp $d/ans.ppm $d/png.ppm || return 1; } || echo "(no imagemagick: ANSI not compared)"
}
check screenshot_key_writes_png_ans_and_a_command_that_reproduces_it screenshot

# A tag file name to find one viewer process by (pgrep -f), unique to this test run.
tagged() { local tag=$OUT/$1-$$.rsc; echo "model $PWD/assets/cube.obj" > "$tag"; echo "$tag"; }
pid_of() { pgrep -f -- "^$BIN .*$1" | head -n 1; }   # rastty, not a shell around it
gone() { ! kill -0 "$1" 2>/dev/null; }

# SIGTERM while the terminal has stopped reading (Ctrl-S: output stalls, the viewer's write
# blocks): the handler must still end the blocked write, drop the queued frame bytes and
# restore the terminal (mouse reports off, main screen, cursor, echo) with status 143.
stalled_term() {
    local s=st$RANDOM f=$OUT/stty-stalled.txt tag; tag=$(tagged stalled)
    tm new-session -d -s $s -x 120 -y 40 \
        "sh -c '$(printf '%q ' "$BIN" --colors truecolor "$tag") 2>/dev/null; echo \$? > $f.rc; stty -a > $f; sleep 60'"
    wait_for 15 hud_has $s " fps" || { echo "viewer did not start"; return 1; }
    tm send-keys -t $s C-s                       # XOFF: the terminal stops taking output
    tm resize-window -t $s -x 200 -y 60          # a full frame, far more than the tty buffers
    sleep $((1 * SLOW))
    local pid; pid=$(pid_of "$tag")
    [ -n "$pid" ] || { echo "no viewer process"; return 1; }
    echo "viewer state while stalled: $(ps -o stat=,wchan= -p "$pid")"
    kill -TERM "$pid"
    wait_for 5 test -s $f || { echo "no exit within 5 s of SIGTERM ($(ps -o stat=,wchan= -p "$pid"))"; return 1; }
    local modes; modes=$(tm display -p -t $s '#{mouse_any_flag} #{mouse_sgr_flag} #{alternate_on} #{cursor_flag}')
    echo "exit status $(cat $f.rc); mouse any, sgr, alternate screen, cursor: $modes"
    [ "$(cat $f.rc)" = 143 ] && [ "$modes" = "0 0 0 1" ] && grep -qE '(^| )echo( |$)' $f &&
        grep -qE '(^| )icanon( |$)' $f
}
check sigterm_on_a_stalled_terminal stalled_term

# Ctrl-Z, then continued in the background (kill -CONT, bg): the terminal is the shell's, so
# the viewer stays stopped instead of drawing into it; SIGTERM then ends it (as `kill %1`,
# which also sends SIGCONT, does) without touching the terminal.
stop_cont_term() {
    local s=sc$RANDOM tag; tag=$(tagged stopcont)
    tm new-session -d -s $s -x 80 -y 24 bash --norc --noprofile
    tm send-keys -t $s "$(printf '%q ' "$BIN" --colors truecolor "$tag")" Enter
    wait_for 15 hud_has $s " fps" || { echo "viewer did not start"; return 1; }
    tm send-keys -t $s C-z
    wait_for 10 sh -c "tmux -L $SOCK capture-pane -t $s -p | grep -q Stopped" || { echo "not stopped"; return 1; }
    local pid; pid=$(pid_of "$tag")
    kill -CONT "$pid"; sleep $((1 * SLOW))
    echo "after SIGCONT in the background: state $(ps -o stat= -p "$pid")"
    kill -TERM "$pid"; kill -CONT "$pid"
    wait_for 5 gone "$pid" || { echo "still there after SIGTERM: state $(ps -o stat= -p "$pid")"; kill -KILL "$pid"; return 1; }
    tm send-keys -t $s "stty -a > $OUT/stty-stopcont.txt" Enter
    wait_for 10 test -s $OUT/stty-stopcont.txt || return 1
    grep -qE '(^| )icanon( |$)' $OUT/stty-stopcont.txt && grep -qE '(^| )echo( |$)' $OUT/stty-stopcont.txt
}
check stopped_continued_viewer_ends_on_sigterm stop_cont_term

# The terminal goes away (its tmux session is killed): the viewer ends, it does not spin.
hangup() {
    local s=hu$RANDOM tag; tag=$(tagged hangup)
    tm new-session -d -s $s -x 80 -y 24 "$(printf '%q ' "$BIN" --colors truecolor "$tag")"
    wait_for 15 hud_has $s " fps" || { echo "viewer did not start"; return 1; }
    local pid; pid=$(pid_of "$tag")
    tm kill-session -t $s
    wait_for 5 gone "$pid" || { echo "still running after the hangup: $(ps -o stat=,pcpu= -p "$pid")"; kill -KILL "$pid"; return 1; }
}
check hung_up_terminal_ends_the_viewer hangup

# A model's warnings (a missing mtllib) go to stderr, which the alternate screen hides until
# the exit: the status line says the first (issue 25).
warning_shown() {
    local d=$OUT/warn; mkdir -p $d
    printf 'mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > $d/m.obj
    tm new-session -d -s wn -x 160 -y 24 "$(printf '%q ' "$BIN" --colors truecolor $d/m.obj); sleep 60"
    wait_for 10 hud_has wn "warning: " || { echo "no warning: $(status_line wn)"; return 1; }
    hud_has wn "m.obj:1: cannot open material library" || { status_line wn; return 1; }
    wait_for 10 hud_has wn " fps" || { echo "the status line did not come back"; return 1; }
    tm kill-session -t wn
}
check a_models_warning_shows_on_the_status_line warning_shown

# TERM=linux and dumb have no alternate screen: q leaves no frame under the prompt (issue 25)
no_alt_screen() {
    local term s
    for term in linux dumb; do
        s=na$term
        tm new-session -d -s $s -x 80 -y 24 "TERM=$term $(printf '%q ' "$BIN") --colors 256 assets/cube.obj; echo EXITED; sleep 60"
        wait_for 15 frame_past $s 0 || { echo "$term: no still picture"; return 1; }
        tm send-keys -t $s q
        wait_for 10 sh -c "tmux -L $SOCK capture-pane -t $s -p | grep -q EXITED" || { echo "$term: q did not quit"; return 1; }
        if tm capture-pane -t $s -p | grep -q '[▀▄]'; then
            echo "TERM=$term: the last frame is still on the screen:"; tm capture-pane -t $s -p | grep -v '^$' | tail -3; return 1
        fi
        tm kill-session -t $s
    done
}
check no_alt_screen_terminal_is_cleared_at_exit no_alt_screen

# --no-hud (issue 25): idle costs no CPU (a status line it never drew kept the loop from
# waiting: ~85 ticks in 2 s), and the viewer, started from a shell, ends when its terminal
# goes away (tmux server killed): it stayed, at ~40 % CPU, deaf to SIGTERM
no_hud_gone() {
    local tag=$PWD/$OUT/rastty-nohud-$$ sock=$SOCK-gone pid a b
    ln -sf "$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")" "$tag"
    tmux -L $sock -f /dev/null new-session -d -s g -x 80 -y 24 "bash --norc --noprofile" || return 1
    tmux -L $sock send-keys -t g "$tag --no-hud --colors truecolor assets/cube.obj" Enter
    wait_for 15 sh -c "tmux -L $sock capture-pane -t g -p | grep -q '[▀▄]'" || { echo "no picture"; tmux -L $sock kill-server; return 1; }
    pid=$(pgrep -f -- "^$tag --no-hud" | head -1)
    [ -n "$pid" ] || { echo "no viewer process"; tmux -L $sock kill-server; return 1; }
    nap 1
    a=$(awk '{print $14 + $15}' /proc/$pid/stat); nap 2; b=$(awk '{print $14 + $15}' /proc/$pid/stat)
    echo "idle: $((b - a)) ticks of CPU in 2 s"
    tmux -L $sock kill-server
    if [ $((b - a)) -gt $((20 * SLOW)) ]; then kill -9 $pid; return 1; fi
    wait_for 10 sh -c "! kill -0 $pid 2>/dev/null" || { echo "still running after its terminal went"; kill -9 $pid; return 1; }
}
check no_hud_viewer_idles_and_ends_with_its_terminal no_hud_gone

# Stopped and continued from outside under an interactive shell (issue 25): continued in the
# background, the viewer gives the terminal back (main screen, mouse off) and waits stopped,
# instead of drawing over the prompt; after fg it repaints in its own modes, and q quits
# without Enter.
external_stop() {
    local s=es$RANDOM tag pid; tag=$(tagged extstop)
    tm new-session -d -s $s -x 80 -y 24 "bash --norc --noprofile -i"
    tm send-keys -t $s "$(printf '%q ' "$BIN" --colors truecolor "$tag")" Enter
    wait_for 15 hud_has $s " fps" || { echo "viewer did not start"; return 1; }
    pid=$(pid_of "$tag")
    kill -STOP "$pid"
    wait_for 10 sh -c "tmux -L $SOCK capture-pane -t $s -p | grep -q Stopped" || { echo "the shell did not see the stop"; kill -CONT $pid; return 1; }
    kill -CONT "$pid"
    wait_for 10 sh -c "[ \"\$(tmux -L $SOCK display -p -t $s '#{alternate_on}#{mouse_any_flag}')\" = 00 ]" ||
        { echo "continued in the background: alternate screen/mouse $(tm display -p -t $s '#{alternate_on}/#{mouse_any_flag}')"; kill -KILL $pid; return 1; }
    tm send-keys -t $s "fg" Enter
    wait_for 15 hud_has $s " fps" || { echo "no repaint after fg"; kill -KILL $pid; return 1; }
    tm send-keys -t $s q
    wait_for 10 gone "$pid" || { echo "q did not quit after fg (raw mode lost?)"; kill -KILL $pid; return 1; }
    tm kill-session -t $s
}
check an_outside_stop_and_continue_leaves_the_prompt_alone external_stop

# A 1000x300 terminal (issue 25): the first frame is drawn whole and then idle costs nothing,
# locally and as over ssh (budgeted frames). The time spent drawing a frame that size was
# taken for the link's (5 KB/s): 'tol 255' for ever, ~115 ticks of CPU in 3 s.
large_window() {
    local env s pid a b n1 n2 log
    for env in "-u SSH_CONNECTION -u SSH_CLIENT -u SSH_TTY" "SSH_CONNECTION=test"; do
        s=lw${env:0:1}; log=$OUT/$s.log
        tm new-session -d -s $s -x 1000 -y 300 \
            "env $env $(printf '%q ' "$BIN") --colors truecolor assets/teapot.obj; sleep 120"
        wait_for 30 frame_past $s 0 || { echo "$env: no whole frame: $(status_line $s | cut -c1-150)"; return 1; }
        tm pipe-pane -o -t $s "cat >> $log"
        pid=$(pgrep -f -- "^$BIN --colors truecolor assets/teapot.obj" | head -1)
        nap 1
        a=$(awk '{print $14 + $15}' /proc/$pid/stat); n1=$(stat -c %s $log)
        nap 2
        b=$(awk '{print $14 + $15}' /proc/$pid/stat); n2=$(stat -c %s $log)
        echo "$env: $(status_line $s | cut -c1-80); idle: $((b - a)) ticks, $((n2 - n1)) bytes in 2 s"
        tm kill-session -t $s
        [ $((b - a)) -le $((20 * SLOW)) ] && [ $((n2 - n1)) -eq 0 ] || return 1
    done
}
check a_1000x300_terminal_draws_its_frame_and_idles large_window

# A 64 KiB stack (ulimit -s 64) runs the viewer (issue 25 item 18): ncurses' newterm and
# setupterm read the terminfo entry into a 32 KiB buffer on their stack, and the viewer died
# of SIGSEGV before its first frame (exit 139); they run on a stack of their own now. A
# COLLADA model (the importer's child, the blended pass), two keys, the help, then q.
small_stack() {
    tm new-session -d -s k64 -x 80 -y 25 \
        "ulimit -s 64; $(printf '%q ' "$BIN" --colors truecolor tests/fuzz/corpus/import/tri.dae); echo EXIT=\$? > $OUT/k64.exit; sleep 120"
    wait_for 15 hud_has k64 " fps" || { echo "no status line; $(cat $OUT/k64.exit 2>/dev/null)"; return 1; }
    still_after k64 0 && keys k64 w a h || return 1
    tm send-keys -t k64 q q
    wait_for 10 test -s $OUT/k64.exit || { echo "did not end"; return 1; }
    cat $OUT/k64.exit
    grep -qx "EXIT=0" $OUT/k64.exit
}
check the_viewer_runs_on_a_64k_stack small_stack

finish
