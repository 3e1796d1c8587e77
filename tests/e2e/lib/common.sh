# tests/e2e/lib/common.sh: helpers for the end-to-end scripts (sourced, not run).
#   check NAME CMD...     run CMD; count a pass or a failure (with NAME and CMD's output)
#   skip NAME REASON      count a skip
#   finish                print "N passed, N failed, N skipped"; exit 1 on failures
#   tm ARGS...            tmux on this script's private socket (killed on exit)
#   wait_for SECS CMD...  poll CMD every 0.1 s until it succeeds or SECS pass
#   ppmstat FILE [BG]     "W H AREA CX CY COLOURS": size, pixels != BG (r,g,b), their
#                         centroid, distinct colours (built from tests/e2e/lib/ppmstat.c)
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
    local log
    if log=$("$@" 2>&1); then
        n_pass=$((n_pass + 1)); echo "ok   $name"
    else
        n_fail=$((n_fail + 1)); echo "FAIL $name"; printf '%s\n' "$log" | sed 's/^/    /' | head -40
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

wait_for() {
    local secs=$1; shift
    local end=$(( $(date +%s%N) / 1000000 + secs * 1000 * SLOW ))
    while [ $(( $(date +%s%N) / 1000000 )) -lt $end ]; do
        "$@" >/dev/null 2>&1 && return 0
        sleep 0.1
    done
    "$@"
}

PPMSTAT=build/e2e/ppmstat
if [ ! -x $PPMSTAT ] || [ tests/e2e/lib/ppmstat.c -nt $PPMSTAT ]; then
    mkdir -p build/e2e && cc -O2 -std=c11 -o $PPMSTAT tests/e2e/lib/ppmstat.c
fi
ppmstat() { $PPMSTAT "$@"; }

# capture the pane (colours kept) into FILE.ans; with `pic`, without the status line
capture() { # capture TARGET FILE [rows_to_keep]
    tm capture-pane -t "$1" -e -N -p > "$2.raw"
    if [ -n "${3:-}" ]; then head -n "$3" "$2.raw" > "$2"; else cp "$2.raw" "$2"; fi
}
# decode a capture to a PPM
decode() { "$BIN" ansi2ppm "$1" --out "$2"; }
