#!/usr/bin/env python3
"""termfilter.py --answers LIST [--log FILE] -- CMD ARGS...: make the terminal around us one that answers
only some queries.

Runs CMD in its own pty and passes its output on to ours with the queries our terminal
should not see taken out, so that the terminal (tmux, which answers them all) answers only
those in LIST, a comma-separated subset of
  dsr   ESC[5n  device status            (tmux, xterm, VTE, kitty, ...; not st)
  cpr   ESC[6n  cursor position report   (every VT100 descendant, st included)
  da1   ESC[c   primary device attributes (every VT100 descendant)
  caps  XTVERSION ESC[>0q, DECRQSS and XTGETTCAP (DCS $q / +q)
or `none` (a terminal that answers nothing at all). st is `cpr,da1`. --log FILE: everything
CMD wrote, queries included (to count them). --cell HxW: answer XTWINOPS 16 (ESC[16t, the
cell's size in pixels) with ESC[6;H;Wt ourselves (tmux does not). --pixels WxH: the pty's
window size in pixels (TIOCGWINSZ's ws_xpixel, ws_ypixel; tmux leaves them 0). Keys typed on our side
reach CMD at once; window size changes are passed on. Exits when CMD exits."""
import fcntl, os, pty, re, select, signal, struct, sys, termios, tty

args = sys.argv[1:]
keep, log, cell, pixels = set(), None, None, None
while args[:1] in (["--answers"], ["--log"], ["--cell"], ["--pixels"]) and len(args) > 1:
    if args[0] == "--answers":
        keep = set(x for x in args[1].split(",") if x and x != "none")
    elif args[0] == "--cell":
        cell = tuple(int(x) for x in args[1].split("x"))
    elif args[0] == "--pixels":
        pixels = tuple(int(x) for x in args[1].split("x"))
    else:
        log = open(args[1], "ab", buffering=0)
    args = args[2:]
if args[:1] != ["--"] or len(args) < 2:
    sys.exit("usage: termfilter.py --answers dsr,cpr,da1,caps|none -- CMD ARGS...")
cmd = args[1:]
QUERIES = {
    "dsr": rb"\x1b\[5n",
    "cpr": rb"\x1b\[\??6n",
    "da1": rb"\x1b\[0?c",
    "caps": rb"\x1b\[>0?q|\x1bP[$+]q[^\x1b]*\x1b\\",
}
drop = [q for k, q in QUERIES.items() if k not in keep] + [rb"\x1b\[16t"]
CELL_Q = b"\x1b[16t"
DROP = re.compile(b"|".join(drop)) if drop else None
# an escape sequence that is complete (a CSI with its final byte, a DCS with its ST, or a
# two-byte escape): anything else at the end of a read is kept for the next one
WHOLE = re.compile(rb"\x1b(?:\[[0-?]*[ -/]*[@-~]|P.*?\x1b\\|[^\[P])", re.S)

pid, fd = pty.fork()
if pid == 0:
    os.execvp(cmd[0], cmd)


def winch(*_):
    try:
        ws = fcntl.ioctl(0, termios.TIOCGWINSZ, b"\0" * 8)
        if pixels:
            rows, cols, _, _ = struct.unpack("HHHH", ws)
            ws = struct.pack("HHHH", rows, cols, pixels[0], pixels[1])
        fcntl.ioctl(fd, termios.TIOCSWINSZ, ws)
        os.kill(pid, signal.SIGWINCH)
    except OSError:
        pass


signal.signal(signal.SIGWINCH, winch)
winch()
saved = termios.tcgetattr(0) if os.isatty(0) else None
if saved:
    tty.setraw(0)
held = b""
try:
    while True:
        try:
            rr, _, _ = select.select([0, fd], [], [])
        except InterruptedError:
            continue
        if 0 in rr:
            data = os.read(0, 4096)
            if data:
                os.write(fd, data)
        if fd in rr:
            try:
                data = os.read(fd, 65536)
            except OSError:
                data = b""
            if not data:
                break
            if log:
                log.write(data)
            buf = held + data
            held = b""
            esc = buf.rfind(b"\x1b", max(0, len(buf) - 512))
            if esc >= 0 and not WHOLE.match(buf, esc):
                buf, held = buf[:esc], buf[esc:]
            if cell:  # answered in the order asked: before the probe's queries reach tmux
                for _ in range(buf.count(CELL_Q)):
                    os.write(fd, b"\x1b[6;%d;%dt" % cell)
            if DROP:
                buf = DROP.sub(b"", buf)
            while buf:
                n = os.write(1, buf)
                buf = buf[n:]
finally:
    if held:
        os.write(1, held)
    if saved:
        termios.tcsetattr(0, termios.TCSADRAIN, saved)
    try:
        _, status = os.waitpid(pid, 0)
    except ChildProcessError:
        status = 0
sys.exit(os.waitstatus_to_exitcode(status) if status else 0)
