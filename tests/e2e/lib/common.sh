# tests/e2e/lib/common.sh: helpers for the end-to-end scripts (sourced, not run).
#   check NAME CMD...     run CMD; count a pass or a failure (with NAME, its time and, when it
#                         fails, CMD's output)
#   skip NAME REASON      count a skip
#   finish                print "N passed, N failed, N skipped"; exit 1 on failures
#   tm ARGS...            tmux on this script's private socket (killed on exit)
#   wait_for SECS CMD...  poll CMD every 0.1 s until it succeeds or SECS pass
#   ppmstat FILE [BG]     "W H AREA CX CY COLOURS": size, pixels != BG (r,g,b), their
#                         centroid, distinct colours (built from tests/e2e/lib/ppmstat.c)
# The viewer in a tmux session S (view_hud.h): once the picture stands still, its status line
# shows "#N", the frames written in full so far, and it is written after the frame: "#N" on
# the screen means all of frame N is. Tests wait for it, never for a quiet screen.
#   status_line S         the last row of S
#   hud_has S TEXT        the status line contains TEXT (a plain string)
#   frame_no S            N of "#N" on the status line; 0 while the picture moves
#   still_after S N       wait until S shows a still picture drawn after frame N
#   keys S KEY...         press each key, then wait for the still picture it leads to
#   log_ends_with_frame LOG N   a pipe-pane LOG has all of frame N: it ends with its status line
# Other programs' output in a pane, once they have written it (exited, say):
#   output_done S         wait until tmux has taken in all output written to session S's
#                         terminal so far: a title (OSC 2) written to the terminal after it
#                         shows in #{pane_title} only once tmux has read what came before
set -u
cd "$(dirname "$0")/../.."
BIN=${RASTTY_BIN:-./rastty}
SLOW=1
[ -n "${RASTTY_ASAN:-}" ] && SLOW=4
OUT=build/e2e/$(basename "$0" .sh)${RASTTY_ASAN:+-asan}
rm -rf "$OUT" && mkdir -p "$OUT"
SHARED=${RASTTY_SHARED:-../shared}/models
SOCK=rastty-e2e-$$
n_pass=0 n_fail=0 n_skip=0

check() {
    local name=$1; shift
    local log t0=$(now_ms) took
    if log=$("$@" 2>&1); then
        took=$(( ($(now_ms) - t0) / 100 ))
        n_pass=$((n_pass + 1)); echo "ok   $name ($((took / 10)).$((took % 10)) s)"
    else
        took=$(( ($(now_ms) - t0) / 100 ))
        n_fail=$((n_fail + 1)); echo "FAIL $name ($((took / 10)).$((took % 10)) s)"
        printf '%s\n' "$log" | sed 's/^/    /' | head -40
    fi
}
skip() { n_skip=$((n_skip + 1)); echo "skip $1: $2"; }
finish() {
    tm kill-server 2>/dev/null
    echo "$n_pass passed, $n_fail failed, $n_skip skipped"
    [ "$n_fail" -eq 0 ]
    exit $?
}
tm() { tmux -L "$SOCK" "$@"; }
trap 'tmux -L "$SOCK" kill-server 2>/dev/null' EXIT
# The private server stays up when its last session ends (exit-empty off): otherwise killing
# the last session makes it exit, and a new-session right after can reach the exiting server
# ("server exited unexpectedly") or lose the new session with it (the quit test's flake).
have_tmux_server() { command -v tmux >/dev/null 2>&1 && tmux -L "$SOCK" -f /dev/null start-server \; set-option -g exit-empty off; }
have_tmux_server 2>/dev/null
have_tmux() { command -v tmux >/dev/null 2>&1; }

# Waiting costs no processes of its own (several suites wait side by side on two cores; a
# process is ~5 ms of CPU here): the clock is $EPOCHREALTIME, and nap sleeps in `read -t`
# on a FIFO nobody writes to.
now_ms() { local t=${EPOCHREALTIME/[.,]/}; echo $(( t / 1000 )); }
_nap=$OUT/.nap; mkfifo "$_nap" && exec {NAP_FD}<>"$_nap"; rm -f "$_nap"
nap() { read -r -t "$1" -u "$NAP_FD" _ 2>/dev/null; true; }
wait_for() {
    local secs=$1; shift
    local t=${EPOCHREALTIME/[.,]/}
    local end=$(( t / 1000 + secs * 1000 * SLOW ))
    while t=${EPOCHREALTIME/[.,]/}; [ $(( t / 1000 )) -lt $end ]; do
        "$@" >/dev/null 2>&1 && return 0
        nap 0.1
    done
    "$@"
}

PPMSTAT=build/e2e/ppmstat
if [ ! -x $PPMSTAT ] || [ tests/e2e/lib/ppmstat.c -nt $PPMSTAT ]; then
    # suites run side by side (tests/run.sh): build beside it, then rename into place
    mkdir -p build/e2e && cc -O2 -std=c11 -o $PPMSTAT.$$ tests/e2e/lib/ppmstat.c && mv -f $PPMSTAT.$$ $PPMSTAT
fi
ppmstat() { $PPMSTAT "$@"; }

# capture the pane (colours kept) into FILE.ans; with `pic`, without the status line
capture() { # capture TARGET FILE [rows_to_keep]
    tm capture-pane -t "$1" -e -N -p > "$2.raw"
    if [ -n "${3:-}" ]; then head -n "$3" "$2.raw" > "$2"; else cp "$2.raw" "$2"; fi
}
# decode a capture to a PPM
decode() { "$BIN" ansi2ppm "$1" --out "$2"; }

# (one tmux process each, the rest in bash: these are what the waits poll)
status_line() {
    local o; o=$(tm capture-pane -t "$1" -p; echo .) # every row, empty ones at the end too
    o=${o%.}; o=${o%$'\n'}; printf '%s\n' "${o##*$'\n'}"
}
hud_has() { [[ $(status_line "$1") == *"$2"* ]]; }
frame_no() {
    if [[ $(status_line "$1") =~ \ \#([0-9]+)(\ |$) ]]; then echo "${BASH_REMATCH[1]}"; else echo 0; fi
}
frame_past() { [ "$(frame_no "$1")" -gt "$2" ]; }
still_after() {
    wait_for 10 frame_past "$1" "$2" ||
        { echo "$1: no still picture after frame #$2; status line: $(status_line "$1")"; return 1; }
}
keys() {
    local s=$1 k n; shift
    for k in "$@"; do
        n=$(frame_no "$s")
        tm send-keys -t "$s" "$k"
        still_after "$s" "$n" || { echo "(after key $k)"; return 1; }
    done
}
# the frame's status line (" #N", the fields after it, SGR 0), then the frame's DSR (none
# when only the status line was drawn): nothing of frame N is still on its way to the log
log_ends_with_frame() {
    local esc=$'\e'
    tail -c 2000 "$1" | LC_ALL=C grep -aqzE " #$2( [^$esc]*)?$esc\[0m($esc\[5n)?\$"
}
output_done() {
    local tag=done-$RANDOM$RANDOM
    printf '\033]2;%s\033\\' "$tag" > "$(tm display -p -t "$1" '#{pane_tty}')"
    wait_for 20 pane_title_is "$1" "$tag" ||
        { echo "$1: output not all in (title: $(tm display -p -t "$1" '#{pane_title}'))"; return 1; }
}
pane_title_is() { [ "$(tm display -p -t "$1" '#{pane_title}')" = "$2" ]; }
