#!/usr/bin/env python3
"""faketerm.py [--answer NAME]... [--seconds S] -- CMD...: a terminal that answers queries.

Runs CMD in a 100x30 pty and plays the terminal: answers every DSR (ESC[5n) with ESC[0n and,
for each --answer, the matching query with what that terminal would say:
  xterm     XTVERSION -> DCS >|XTerm(379) ST;  DECRQSS m -> DCS 1$r0;48:2::1:2:3m ST
  oldxterm  XTVERSION -> DCS >|XTerm(330) ST;  DECRQSS m -> DCS 1$r0;48;5;16m ST
  kitty     XTVERSION -> DCS >|kitty(0.26.5) ST;  XTGETTCAP RGB -> DCS 1+r524742=38 ST
  (nothing: answers DSR only, like urxvt or GNU screen)
Once the viewer's picture stands still (a status line with the frame count "#N", which the
viewer writes after the whole frame: view_hud.h), or after S seconds (default 10) without,
it types q and prints the last status line drawn (the text after ESC[30;1H and the status
line's SGR). Exit status 1 if none was drawn."""
import os, pty, re, select, sys, time, fcntl, termios, struct

args = sys.argv[1:]
answers, seconds = [], 10.0
while args and args[0] != "--":
    if args[0] == "--answer":
        answers.append(args[1]); args = args[2:]
    elif args[0] == "--seconds":
        seconds = float(args[1]); args = args[2:]
    else:
        sys.exit("faketerm: unknown argument " + args[0])
cmd = args[1:]
REPLIES = {
    "xterm": {b"\x1b[>0q": b"\x1bP>|XTerm(379)\x1b\\", b"\x1bP$qm\x1b\\": b"\x1bP1$r0;48:2::1:2:3m\x1b\\"},
    "oldxterm": {b"\x1b[>0q": b"\x1bP>|XTerm(330)\x1b\\", b"\x1bP$qm\x1b\\": b"\x1bP1$r0;48;5;16m\x1b\\"},
    "kitty": {b"\x1b[>0q": b"\x1bP>|kitty(0.26.5)\x1b\\", b"\x1bP+q524742\x1b\\": b"\x1bP1+r524742=38\x1b\\"},
}
# the status line: row 30, black on white (plain SGR 0 in --colors none)
HUD = re.compile(rb"\x1b\[30;1H\x1b\[0(?:;30;47)?m([^\x1b]*)")


def still(out):
    """the last status line drawn has the frame count: the picture stands still"""
    last = None
    for last in HUD.finditer(out):
        pass
    return last is not None and re.search(rb" #[0-9]+( |$)", last.group(1)) is not None


pid, fd = pty.fork()
if pid == 0:
    os.execvp(cmd[0], cmd)
fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
out, seen, end, quit_sent = b"", 0, time.time() + seconds, False
while True:
    r, _, _ = select.select([fd], [], [], 0.05)
    if r:
        try:
            data = os.read(fd, 65536)
        except OSError:
            break
        if not data:
            break
        out += data
        # answer queries in the order they came, the DSR last (as a terminal does)
        while True:
            hits = [(out.find(q, seen), q, a) for name in answers for q, a in REPLIES[name].items()]
            hits += [(out.find(b"\x1b[5n", seen), b"\x1b[5n", b"\x1b[0n")]
            hits = [h for h in hits if h[0] >= 0]
            if not hits:
                break
            i, q, a = min(hits)
            os.write(fd, a)
            seen = i + len(q)
    if not quit_sent and (time.time() > end or still(out)):
        os.write(fd, b"q"); quit_sent = True
    if quit_sent and time.time() > end + 5:
        break
try:
    os.waitpid(pid, 0)
except ChildProcessError:
    pass
hud = HUD.findall(out)
if not hud:
    print("no status line; output began %r" % out[:200]); sys.exit(1)
print(hud[-1].decode("utf-8", "replace").rstrip())
