#!/usr/bin/env bash
# tests/bench_first_frame.sh: how soon the viewer shows a big model (part of `make bench`;
# numbers, never verdicts). Issue 24's target: a 1M-triangle file's first frame within 1 s.
# The 1M-triangle displaced sphere (build/bench/gensphere, as tests/bench_scale.sh makes it)
# opened by the viewer in a 160x48 tmux pane, RUNS times (default 5) per --lod mode, the
# modes interleaved. The times are the viewer's own (RASTTY_FRAME_LOG,
# include/viewer/view_frames.h: a line per phase and per frame written, on CLOCK_MONOTONIC),
# from a stamp taken just before the exec (python's time.monotonic, the same clock):
#   exec->frame  the exec to the first frame's bytes written to the terminal;
#   start        the exec to view_run (the process's own start: linking, options);
#   load         the model read and built (view_run to "loaded");
#   terminal     the terminal opened and its probes answered;
#   frame        from there to the first frame written (drawn, encoded);
#   levels       the exec to the levels of detail being in ("-": not built, --lod off).
# Medians over the runs, with min-max; the load average before and after.
# BINS="A B" compares binaries (each labelled by its path), interleaved run by run.
# N=triangles (default 1000000).
set -u
cd "$(dirname "$0")/.."
BINS=${BINS:-${RASTTY_BIN:-./rastty}}
RUNS=${RUNS:-5}
N=${N:-1000000}
MODES=${MODES:-off auto}
D=build/bench/first_frame
mkdir -p "$D"
if ! command -v tmux >/dev/null; then
    echo "-- skipped first-frame benchmark: no tmux"
    exit 0
fi
[ -x build/bench/gensphere ] || make -s build/bench/gensphere >/dev/null
ply=build/bench/scale/s$N.ply
mkdir -p build/bench/scale
[ -f "$ply" ] || build/bench/gensphere "$N" "$ply" >/dev/null
sock=rastty-ff-$$
trap 'tmux -L $sock kill-server 2>/dev/null' EXIT
# run BIN MODE OUT: one viewer start; appends "exec start load terminal frame levels" to OUT
run() {
    local bin=$1 mode=$2 out=$3 log=$D/run.log stamp=$D/run.stamp
    rm -f "$log" "$stamp"
    tmux -L $sock -f /dev/null new-session -d -s x -x 160 -y 48 \
        "env RASTTY_FRAME_LOG=$PWD/$log /usr/bin/python3 -c 'import os, sys, time
open(sys.argv[1], \"w\").write(\"%.6f\" % time.monotonic())
os.execv(sys.argv[2], sys.argv[2:])' $PWD/$stamp $bin --colors truecolor --lod $mode $PWD/$ply; sleep 60"
    # wait for the first frame (and under auto the levels) in the log, at most 60 s
    local want='^frame 1 '
    [ "$mode" = off ] || want='^levels-ready '
    for _ in $(seq 600); do
        grep -q "$want" "$log" 2>/dev/null && break
        sleep 0.1
    done
    tmux -L $sock kill-server 2>/dev/null
    /usr/bin/python3 - "$stamp" "$log" >>"$out" <<'PY'
import sys
stamp = float(open(sys.argv[1]).read())
ph = {}
for line in open(sys.argv[2]):
    f = line.split()
    if not f:
        continue
    if f[0] == "start":
        ph["start"] = float(f[2])
    elif f[0] in ("loaded", "terminal", "levels-ready") or (f[0] == "frame" and f[1] == "1"):
        ph.setdefault(f[0], float(f[2] if f[0] != "frame" else f[3]))
s = ph["start"]
print("%.4f %.4f %.4f %.4f %.4f %s" % (
    s + ph["frame"] - stamp, s - stamp, ph["loaded"], ph["terminal"] - ph["loaded"],
    ph["frame"] - ph["terminal"],
    "%.4f" % (s + ph["levels-ready"] - stamp) if "levels-ready" in ph else "-"))
PY
}
echo "-- first frame of a $N-triangle file in the viewer (tmux 160x48, $RUNS runs per mode,"
echo "   interleaved; seconds, median [min-max]); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for ((r = 0; r < RUNS; r++)); do
    for bin in $BINS; do
        for mode in $MODES; do
            run "$bin" "$mode" "$D/$(echo "$bin" | tr / _).$mode.txt.$$" || true
        done
    done
done
for bin in $BINS; do
    for mode in $MODES; do
        f="$D/$(echo "$bin" | tr / _).$mode.txt.$$"
        printf '%-24s --lod %-5s ' "$bin" "$mode"
        /usr/bin/python3 - "$f" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
def col(i, name):
    v = [float(r[i]) for r in rows if r[i] != "-"]
    if not v:
        return "%s -" % name
    return "%s %.2f [%.2f-%.2f]" % (name, statistics.median(v), min(v), max(v))
print("  ".join([col(0, "exec->frame"), col(1, "start"), col(2, "load"), col(3, "terminal"),
                 col(4, "frame"), col(5, "levels")]) + "  (%d runs)" % len(rows))
PY
        rm -f "$f"
    done
done
echo "   load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
