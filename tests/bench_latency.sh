#!/usr/bin/env bash
# tests/bench_latency.sh: key -> screen latency of the viewer (part of `make bench`; numbers,
# never verdicts). The textured shared head spinning in truecolor in a 160x48 tmux pane;
# 20 presses of f, each timed until the status line shows it (tests/e2e/lib/keylat.py),
#   rates:     behind ../shared/tools/slowlink.py (1 MB queue, the viewer told it is over ssh)
#              at 256 kbit/s, 1 Mbit/s and 4 Mbit/s, and unthrottled (the pane itself, local)
#   terminals: tmux as it is (answers every query), st (answers CPR and DA1, never DSR), a
#              DA1-only terminal and one that answers nothing (tests/e2e/lib/termfilter.py
#              takes the other queries out before tmux sees them)
# The issue's bar: median <= 100 ms and worst <= 200 ms at every rate in every terminal that
# answers something. PRESSES=N for fewer presses.
set -u
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
S=${RASTTY_SHARED:-../shared}
LINK=$S/tools/slowlink.py
HEAD=$S/models/african_head/african_head.obj
D=build/bench
mkdir -p "$D"
if [ ! -f "$LINK" ] || [ ! -f "$HEAD" ] || ! command -v tmux >/dev/null; then
    echo "-- skipped latency benchmark: no $LINK, shared african_head or tmux"
    exit 0
fi
echo "-- key -> screen latency, ms (median / worst of ${PRESSES:-20} presses of f, the status line"
echo "   timed), the textured head spinning in truecolor in 160x48; link bytes/s in brackets"
printf '   %-22s' terminal
for rate in "256 kbit/s" "1 Mbit/s" "4 Mbit/s" unthrottled; do printf '%-22s' "$rate"; done
echo
# the floor: what the measuring itself costs on this machine now (tmux, the pollers, the
# scheduler): a still cube in 80x24, local; the load average beside it
out=$(/usr/bin/python3 tests/e2e/lib/keylat.py --socket "rastty-lat-$$" --rate 0 --queue 0 \
      --size 80x24 --presses "${PRESSES:-20}" -- "$BIN" --colors truecolor assets/cube.obj 2>&1)
[[ $out =~ median\ ([0-9]+)\ worst\ ([0-9]+) ]] &&
    echo "   floor (a still cube, 80x24, local): ${BASH_REMATCH[1]} / ${BASH_REMATCH[2]} ms; load average $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
for term in "tmux dsr,cpr,da1,caps" "st cpr,da1" "da1-only da1" "silent none"; do
    set -- $term
    printf '   %-22s' "$1 ($2)"
    for rate in 32000 128000 512000 0; do
        out=$(/usr/bin/python3 tests/e2e/lib/keylat.py --socket "rastty-lat-$$" --rate "$rate" \
              --queue 1000000 --size 160x48 --presses "${PRESSES:-20}" --slowlink "$LINK" \
              --answers "$2" --log "$D/lat-$1-$rate.log" -- \
              "$BIN" --colors truecolor --spin "$HEAD" 2>&1)
        if [[ $out =~ median\ ([0-9]+)\ worst\ ([0-9]+).*bytes/s\ ([0-9-]+) ]]; then
            printf '%-22s' "${BASH_REMATCH[1]} / ${BASH_REMATCH[2]} [$((BASH_REMATCH[3] / 1000))K]"
        else
            printf '%-22s' "failed"
            echo "$out" | tail -n 2 >> "$D/lat-failures.log"
        fi
    done
    echo
done
