#!/usr/bin/env bash
# colours.sh (issue 11): which colour mode the viewer picks, and the user's defaults.
#   - inside tmux without COLORTERM (stock tmux, or ssh into one): truecolor, from tmux's
#     record of its client (client_termfeatures) or, with no client attached, its XTVERSION
#   - elsewhere the terminal's own answers (tests/e2e/lib/faketerm.py plays xterm, an old
#     xterm, kitty, and a terminal that answers only DSR)
#   - RASTTY_COLORS and the config file set a default; --colors beats both; a bad line in
#     the file is a file:line error; spin-timeout stops an untouched spin
source "$(dirname "$0")/lib/common.sh"

FAKE="/usr/bin/python3 tests/e2e/lib/faketerm.py"
CUBE=$PWD/assets/cube.obj
# status_of [faketerm args] -- ENV...: the status line the viewer draws under faketerm
status_of() { $FAKE "$@"; }
# mode_is WANT LINE: the status line's colour field is WANT
mode_is() { echo "status: $2"; echo "$2" | grep -q "| $1 | "; }

env_base=(env -u TMUX -u COLORTERM -u RASTTY_COLORS -u XTERM_VERSION -u VTE_VERSION
          -u KITTY_WINDOW_ID -u TERM_PROGRAM -u LC_TERMINAL XDG_CONFIG_HOME=$OUT/nocfg)
answers() {
    mode_is 256 "$(status_of -- "${env_base[@]}" TERM=xterm-256color "$BIN" "$CUBE")" || return 1
    mode_is truecolor "$(status_of --answer xterm -- "${env_base[@]}" TERM=xterm "$BIN" "$CUBE")" || return 1
    mode_is 256 "$(status_of --answer oldxterm -- "${env_base[@]}" TERM=xterm-256color "$BIN" "$CUBE")" || return 1
    mode_is truecolor "$(status_of --answer kitty -- "${env_base[@]}" TERM=xterm-256color "$BIN" "$CUBE")"
}
check terminal_answers_choose_truecolor answers

defaults() {
    mkdir -p $OUT/cfg/rastty
    mode_is 16 "$(status_of --answer xterm -- "${env_base[@]}" RASTTY_COLORS=16 TERM=xterm "$BIN" "$CUBE")" || return 1
    printf 'colors = none\n' > $OUT/cfg/rastty/config
    local line; line=$(status_of --answer xterm -- "${env_base[@]}" XDG_CONFIG_HOME=$OUT/cfg TERM=xterm "$BIN" "$CUBE")
    mode_is none "$line" || return 1
    mode_is 256 "$(status_of -- "${env_base[@]}" XDG_CONFIG_HOME=$OUT/cfg RASTTY_COLORS=256 TERM=xterm "$BIN" "$CUBE")" || return 1
    mode_is truecolor "$(status_of -- "${env_base[@]}" XDG_CONFIG_HOME=$OUT/cfg RASTTY_COLORS=16 TERM=xterm "$BIN" --colors truecolor "$CUBE")"
}
check rastty_colors_and_config_file_set_the_default defaults

bad_config() {
    mkdir -p $OUT/bad/rastty
    printf 'colors = 256\nspin = sometimes\n' > $OUT/bad/rastty/config
    local err rc
    err=$(XDG_CONFIG_HOME=$OUT/bad "$BIN" "$CUBE" 2>&1 </dev/null); rc=$?
    echo "exit $rc: $err"
    [ $rc = 2 ] && echo "$err" | grep -q "bad/rastty/config:2: spin: expected on or off"
}
check config_file_error_names_file_and_line bad_config

if ! have_tmux; then
    skip truecolor_inside_tmux_without_colorterm "tmux not installed"
    skip spin_timeout_stops_streaming "tmux not installed"
    finish
fi

# stock tmux: TERM=tmux-256color, no COLORTERM. Detached (no client): tmux's XTVERSION. With
# a client attached (a second tmux server's pane): tmux's client_termfeatures.
in_tmux() {
    tm new-session -d -s t1 -x 120 -y 24 "env -u COLORTERM TERM=tmux-256color $(printf '%q ' "$BIN" "$CUBE"); sleep 30"
    wait_for 15 hud_has t1 " fps" || return 1
    echo "detached: $(tm capture-pane -t t1 -p | tail -n 1 | cut -c1-70)"
    hud_has t1 "| truecolor |" || return 1
    local outer=$SOCK-outer
    tm new-session -d -s t2 -x 120 -y 24 "sleep 60"
    tmux -L $outer -f /dev/null new-session -d -x 120 -y 25 "env -u COLORTERM TMUX= tmux -L $SOCK attach -t t2"
    wait_for 10 sh -c "tmux -L $SOCK list-clients | grep -q t2" || { tmux -L $outer kill-server; echo "no client"; return 1; }
    echo "client features: $(tm display -p -t t2 '#{client_termfeatures}')"
    tm new-window -t t2 "env -u COLORTERM TERM=tmux-256color $(printf '%q ' "$BIN" "$CUBE"); sleep 30"
    wait_for 15 hud_has t2 " fps" || { tmux -L $outer kill-server; return 1; }
    echo "attached: $(tm capture-pane -t t2 -p | tail -n 1 | cut -c1-70)"
    hud_has t2 "| truecolor |"; local rc=$?
    tmux -L $outer kill-server
    # the outer client gone from this server too: while it lingers, tmux sizes a new
    # session's window to it (120 columns), and the spin test's 200-column status line
    # would lose its "spin paused" field (seen once under the full suite's load)
    wait_for 10 sh -c "! tmux -L $SOCK list-clients 2>/dev/null | grep -q ." || rc=1
    return $rc
}
check truecolor_inside_tmux_without_colorterm in_tmux

# spin-timeout from the config file: a spin nobody touches pauses, and the bytes stop
spin_timeout() {
    mkdir -p $OUT/st/rastty
    printf 'spin-timeout = 1\n' > $OUT/st/rastty/config
    local log=$OUT/spin.log
    tm new-session -d -s sp -x 200 -y 24 "XDG_CONFIG_HOME=$OUT/st $(printf '%q ' "$BIN" --colors truecolor --spin "$CUBE"); sleep 30"
    wait_for 15 hud_has sp " fps" || return 1
    : > $log; tm pipe-pane -o -t sp "cat >> $log"
    # it pauses after a second; the message about it goes; the status line says so
    wait_for 10 hud_has sp "| spin paused |" || { echo "status: $(tm capture-pane -t sp -p | tail -n 1)"; return 1; }
    local n; n=$(frame_no sp)
    wait_for 5 log_ends_with_frame $log "$n" || { echo "the log does not end with frame #$n"; return 1; }
    local s0 s1; s0=$(stat -c %s $log); sleep 1; s1=$(stat -c %s $log)
    echo "bytes before: $s0; in the second after: $((s1 - s0))"
    [ "$s1" -eq "$s0" ] && [ "$s0" -gt 0 ]
}
check spin_timeout_stops_streaming spin_timeout

finish
