#!/usr/bin/env bash
# tests/bench_link.sh: what reaches the screen over a slow link (part of `make bench`; numbers,
# never verdicts). The demo scene in a 160x48 tmux pane behind ../shared/tools/slowlink.py
# (1 MB queue, the viewer told it is over ssh) for SECS seconds (default 8); the viewer
# decodes every frame it writes and logs its PSNR against the framebuffer it came from
# (RASTTY_FRAME_LOG, include/viewer/view_frames.h). Per rate: frames written, the first
# frame's arrival time (its bytes at the link's rate), PSNR min / median, and how many frames
# fell below 30 dB (the issue's bar: none) — with the quality floor (now) and without it
# (RASTTY_FRAME_FLOOR=off, the viewer before it), for the demo's own spin and for --spin.
set -u
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
S=${RASTTY_SHARED:-../shared}
LINK=$S/tools/slowlink.py
D=build/bench/link
SECS=${SECS:-8}
mkdir -p "$D"
if [ ! -f "$LINK" ] || ! command -v tmux >/dev/null; then
    echo "-- skipped link benchmark: no $LINK or tmux"
    exit 0
fi
sock=rastty-link-$$
trap 'tmux -L $sock kill-server 2>/dev/null' EXIT
# run NAME RATE FLOOR ARGS...: the log of one run
run() {
    local name=$1 rate=$2 floor=$3; shift 3
    local log=$D/$name.log
    rm -f "$log"
    tmux -L $sock -f /dev/null new-session -d -s x -x 160 -y 48 \
        "env RASTTY_FRAME_FLOOR=$floor RASTTY_FRAME_LOG=$PWD/$log /usr/bin/python3 $LINK $rate 1000000 -- env 'SSH_CONNECTION=127.0.0.1 40000 127.0.0.1 22' $BIN --colors truecolor $*; sleep 60"
    sleep "$SECS"
    tmux -L $sock kill-server 2>/dev/null
    # the frames written in the first SECS s (those the link delivered by then, roughly)
    /usr/bin/python3 - "$log" "$rate" "$SECS" <<'PY'
import statistics, sys
log, rate, secs = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
db, sent, first = [], 0, None
for line in open(log):
    f = line.split()
    if not f or f[0] != "frame":
        continue
    t, b, p = float(f[3]), int(f[5]), f[11]
    sent += b
    if first is None:
        first = t + b / rate
    if t + sent / rate > secs:  # still on its way at the end
        break
    db.append(99.0 if p == "inf" else float(p))
if not db:
    print("no frame arrived")
else:
    print("%4d frames  first %5.2f s  PSNR min %6.2f  median %6.2f  below 30 dB %d"
          % (len(db), first, min(db), statistics.median(db), sum(d < 30 for d in db)))
PY
}
echo "-- what reaches the screen over a slow link: the demo, 160x48, ${SECS} s, per frame the"
echo "   decoded screen against its framebuffer (floor off = the viewer before the quality floor)"
for rate in 32000 128000; do
    label=$([ $rate = 32000 ] && echo "256 kbit/s" || echo "1 Mbit/s")
    for spin in "demo's own spin|" "--spin|--spin"; do
        for floor in off on; do
            printf '   %-11s %-17s floor %-4s' "$label" "${spin%%|*}" "$floor"
            run "demo-$rate-${spin#*|}-$floor" $rate $floor ${spin#*|}
        done
    done
done
