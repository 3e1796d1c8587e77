#!/usr/bin/env bash
# terminals.sh (issue 25): terminals that answer only some queries, and a local terminal.
# tests/e2e/lib/termfilter.py sits between tmux and the viewer and takes out the queries the
# terminal should not see, so tmux answers only the others: `cpr,da1` is st (it answers
# ESC[6n and ESC[c, never ESC[5n), `da1` an even plainer VT100, `none` a terminal (or a link)
# that answers nothing at all. Its --log has every byte the viewer wrote, queries included.
#   - each is paced on the one query it answers, asked after every frame, and the others are
#     asked once, at start: counted in the log (a per-frame 2-second timeout on an unanswered
#     query is what made st take 2.6 s a key)
#   - frames flow: the status line's frame rate while spinning is far above the 0.5 fps a
#     timeout a frame allows (a generous bound: the tight numbers are make bench's latency)
#   - a local terminal (no ssh) is paced by its answers but never budgeted: a heavy model
#     spinning never shows "link ..: tol N" and never drops to 256 colours
source "$(dirname "$0")/lib/common.sh"

NAMES=(st_answers_only_cpr_and_is_paced_on_it da1_only_is_paced_on_da1
       a_terminal_that_answers_nothing_is_asked_once tmux_is_paced_on_dsr
       a_local_terminal_is_never_taken_for_a_slow_link)
if ! have_tmux; then
    for n in "${NAMES[@]}"; do skip "$n" "tmux not installed"; done
    finish
fi
FILTER=tests/e2e/lib/termfilter.py

# behind ANSWERS, spin MODEL in session S (80x24); the viewer's bytes in $OUT/S.log
start_behind() {
    local s=$1 answers=$2; shift 2
    : > "$OUT/$s.log"
    tm new-session -d -s "$s" -x 80 -y 24 \
        "$(printf '%q ' /usr/bin/python3 "$FILTER" --answers "$answers" --log "$OUT/$s.log" -- \
           "$BIN" --colors truecolor "$@"); echo EXIT=\$? > $OUT/$s.exit; sleep 120"
    wait_for 15 hud_has "$s" " fps" || { echo "no status line"; tm capture-pane -t "$s" -p | tail -3; return 1; }
}
fps_of() { [[ $(status_line "$1") =~ \ ([0-9]+)\ fps ]] && echo "${BASH_REMATCH[1]}" || echo 0; }
fps_at_least() { [ "$(fps_of "$1")" -ge "$2" ]; }
# count S QUERY: how many times the viewer asked QUERY (a literal, ESC as \e)
count() { LC_ALL=C grep -aoF "$(printf "$2")" "$OUT/$1.log" | wc -l; }
asked_more_than() { [ "$(count "$1" "$2")" -gt "$3" ]; }

# paced S ANSWERS PER_FRAME: spinning behind ANSWERS, at least 5 fps; the PER_FRAME query
# asked with every frame (> 20 times), each of the others once (the start's probe)
paced() {
    local s=$1 answers=$2 per=$3 q n
    start_behind "$s" "$answers" --spin assets/teapot.obj || return 1
    wait_for 20 fps_at_least "$s" 5 || { echo "frame rate: $(status_line "$s")"; return 1; }
    [ "$per" = none ] || wait_for 20 asked_more_than "$s" "$per" 20 || true
    tm send-keys -t "$s" q
    wait_for 10 test -f "$OUT/$s.exit" || { echo "q did not quit"; return 1; }
    for q in '\e[5n' '\e[6n' '\e[c'; do
        n=$(count "$s" "$q")
        if [ "$q" = "$per" ]; then
            [ "$n" -gt 20 ] || { echo "$q asked $n times: not with every frame"; return 1; }
        else
            [ "$n" -eq 1 ] || { echo "$q asked $n times, want once (the start's probe)"; return 1; }
        fi
    done
}
check st_answers_only_cpr_and_is_paced_on_it paced st cpr,da1 '\e[6n'
check da1_only_is_paced_on_da1 paced da1 da1 '\e[c'
check a_terminal_that_answers_nothing_is_asked_once paced none none none
check tmux_is_paced_on_dsr paced all dsr,cpr,da1,caps '\e[5n'

# The textured head spinning in 160x48, local: for 4 s the status line (sampled every 0.2 s)
# never reports a link, a tolerance or 256 colours. Without ssh the link is this machine.
local_link() {
    local head=$SHARED/african_head/african_head.obj s=loc line i
    [ -f "$head" ] || head=assets/teapot.obj
    tm new-session -d -s $s -x 160 -y 48 \
        "$(printf '%q ' env -u SSH_CONNECTION -u SSH_TTY -u SSH_CLIENT "$BIN" --colors truecolor --spin "$head"); sleep 120"
    wait_for 15 hud_has $s " fps" || { echo "no status line"; return 1; }
    for i in $(seq 20); do
        line=$(status_line $s)
        if [[ $line == *"KB/s"* || $line == *" tol "* || $line == *"256c"* || $line == *"| 256 |"* ]]; then
            echo "a local terminal taken for a slow link: $line"; return 1
        fi
        nap 0.2
    done
}
check a_local_terminal_is_never_taken_for_a_slow_link local_link

finish
