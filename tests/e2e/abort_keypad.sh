#!/usr/bin/env bash
# abort_keypad.sh: a viewer that dies by SIGABRT (or SIGSEGV) leaves the terminal's cursor
# keys and keypad in normal mode, as ncurses' keypad(TRUE) found them: tmux's pane flags
# keypad_cursor_flag (DECCKM) and keypad_flag (DECKPAM) are back to 0.
source "$(dirname "$0")/lib/common.sh"

if ! have_tmux; then
    skip abort_restores_keypad_mode "tmux not installed"
    finish
fi

crash_keypad() {
    local sig rc=0
    for sig in ABRT SEGV; do
        local s=k$RANDOM tag=$OUT/keypad-$sig-$$.rsc
        echo "model $PWD/assets/cube.obj" > "$tag"
        tm new-session -d -s $s -x 80 -y 24 "sh -c '$(printf '%q ' "$BIN" --colors truecolor "$tag") 2>/dev/null; sleep 60'"
        # running, with keypad-transmit mode on
        if ! wait_for 15 sh -c "tmux -L $SOCK capture-pane -t $s -p | grep -q fps"; then
            echo "$sig: viewer did not start"; rc=1; tm kill-session -t $s; continue
        fi
        local before; before=$(tm display -p -t $s '#{keypad_cursor_flag}#{keypad_flag}')
        pkill -$sig -f -- "^$BIN .*$tag"
        wait_for 10 sh -c "! pgrep -f -- '^$BIN .*$tag' > /dev/null"
        output_done $s || rc=1                   # what the viewer wrote as it died is all in
        local after; after=$(tm display -p -t $s '#{keypad_cursor_flag}#{keypad_flag}')
        echo "$sig: keypad flags before $before, after $after"
        [ "$before" != 00 ] || { echo "$sig: the viewer never entered keypad mode (test broken)"; rc=1; }
        [ "$after" = 00 ] || rc=1
        tm kill-session -t $s
    done
    return $rc
}
check abort_restores_keypad_mode crash_keypad

finish
