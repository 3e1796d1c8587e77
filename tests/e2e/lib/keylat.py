#!/usr/bin/env python3
"""keylat.py: key -> screen latency of the viewer behind a slow link, measured in tmux.

  keylat.py --socket NAME --rate BYTES_PER_S --queue BYTES --size COLSxROWS
            [--presses N] [--warmup S] [--slowlink PATH] [--answers LIST] -- CMD ARGS...

Starts CMD in a detached tmux session of that size, behind ../shared/tools/slowlink.py (its
output leaves at RATE bytes/s through a QUEUE-byte buffer: a slow SSH link), waits for the
status line (RATE 0: no slowlink, the pane itself, a local terminal; else the command runs
with SSH_CONNECTION set, as over ssh; --answers LIST: behind
tests/e2e/lib/termfilter.py, a terminal that answers only those queries, e.g. cpr,da1 = st), lets the link reach its steady state (--warmup seconds), then N times: waits a
random 0.2..0.7 s (so presses land anywhere in a frame), presses `f` and polls the status line
(`capture-pane`, every ~5 ms) until the texture filter it names has flipped (nearest <->
bilinear). Prints one line per press and a summary:
  latency ms: median M worst W (N presses); link bytes/s B
B counts what left the link (pipe-pane) during the presses. Exit status 1 if a press never
showed (20 s) or the viewer did not start. No verdicts otherwise: callers compare the numbers.
"""
import argparse, os, random, shlex, statistics, subprocess, sys, time

ap = argparse.ArgumentParser()
ap.add_argument("--socket", required=True)
ap.add_argument("--rate", type=float, required=True)
ap.add_argument("--queue", type=int, required=True)
ap.add_argument("--size", default="160x48")
ap.add_argument("--presses", type=int, default=12)
ap.add_argument("--warmup", type=float, default=3.0)
ap.add_argument("--timeout", type=float, default=20.0)
ap.add_argument("--slowlink", default=os.path.join(os.environ.get("RASTTY_SHARED", "../shared"),
                                                    "tools", "slowlink.py"))
ap.add_argument("--answers", default=None,
                help="the terminal answers only these queries (tests/e2e/lib/termfilter.py)")
ap.add_argument("--log", default=None, help="file for the pane's output (bytes counted)")
ap.add_argument("cmd", nargs=argparse.REMAINDER)
a = ap.parse_args()
cmd = a.cmd[1:] if a.cmd and a.cmd[0] == "--" else a.cmd
cols, rows = (int(x) for x in a.size.split("x"))
S = "lat"


def tm(*args, check=True):
    return subprocess.run(["tmux", "-L", a.socket] + list(args), capture_output=True,
                          text=True, check=check).stdout


def status():
    return tm("capture-pane", "-p", "-t", S, "-S", str(rows - 1), "-E", str(rows - 1),
              check=False)


CYCLE = ["nearest", "bilinear", "trilinear"]  # the f key's order


def filt(line):
    for f in CYCLE:
        if " " + f + " " in line:
            return f
    return None


# behind the link the viewer is told it is over ssh, as sshd would (SSH_CONNECTION): a local
# terminal's answers only pace the frames (pace.h), a link's also size them
link = ["/usr/bin/python3", a.slowlink, str(int(a.rate)), str(a.queue), "--", "env",
        "SSH_CONNECTION=127.0.0.1 40000 127.0.0.1 22"] if a.rate > 0 else []
if a.answers is not None:  # the terminal side of the link answers only some queries
    here = os.path.dirname(os.path.abspath(__file__))
    link = ["/usr/bin/python3", os.path.join(here, "termfilter.py"), "--answers", a.answers,
            "--"] + link
inner = " ".join(shlex.quote(x) for x in link + cmd)
tm("new-session", "-d", "-s", S, "-x", str(cols), "-y", str(rows), inner + "; sleep 30")
log = a.log or "/dev/null"
try:
    end = time.monotonic() + 30
    while time.monotonic() < end and filt(status()) is None:
        time.sleep(0.05)
    if filt(status()) is None:
        print("viewer did not start; status line: %r" % status().strip())
        sys.exit(1)
    time.sleep(a.warmup)
    if a.log:
        open(a.log, "wb").close()
        tm("pipe-pane", "-o", "-t", S, "cat >> " + shlex.quote(a.log))
    t_start = time.monotonic()
    lat = []
    for i in range(a.presses):
        time.sleep(random.uniform(0.2, 0.7))
        before = filt(status())
        want = CYCLE[(CYCLE.index(before) + 1) % len(CYCLE)] if before else None
        t0 = time.monotonic()
        tm("send-keys", "-t", S, "f")
        seen = None
        while time.monotonic() - t0 < a.timeout:
            if filt(status()) == want:
                seen = time.monotonic()
                break
            time.sleep(0.004)
        if seen is None:
            print("press %d: no change within %.0f s (status: %r)" % (i + 1, a.timeout,
                                                                     status().strip()))
            sys.exit(1)
        lat.append((seen - t0) * 1e3)
        print("press %2d: %6.0f ms" % (i + 1, lat[-1]))
    elapsed = time.monotonic() - t_start
    nbytes = os.path.getsize(a.log) if a.log else 0
    print("latency ms: median %.0f worst %.0f (%d presses); link bytes/s %.0f"
          % (statistics.median(lat), max(lat), len(lat), nbytes / elapsed if a.log else -1))
finally:
    tm("kill-server", check=False)
