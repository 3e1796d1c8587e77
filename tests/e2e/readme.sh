#!/usr/bin/env bash
# readme.sh (issue 25): every line of the README's usage block runs as written, from a clone
# whose ../shared holds the shared models (the block's $S and $H). The lines run in a folder
# made like a fresh clone ($OUT/clone: ./rastty and assets/ linked in, ../shared beside it).
#   - a variable line (S=... H=...) is kept for the lines after it
#   - the viewer (./rastty without a subcommand) runs in tmux: its status line shows, q quits
#     it, exit status 0
#   - `make TARGET`: the target exists and its recipe resolves (make -n: nothing is built)
#   - `./rastty bench --chart` (minutes of measuring): runs 20 s without an error
#   - every other line: exit status 0
source "$(dirname "$0")/lib/common.sh"

ROOT=$PWD
SHARED_DIR=${RASTTY_SHARED:-../shared}
block() { awk '/^## Usage/ { u = 1 } u && /^```sh$/ { on = 1; next } on && /^```$/ { exit } on' README.md; }
if [ ! -d "$SHARED_DIR/models/african_head" ]; then
    skip readme_usage_lines_run_as_written "no shared models at $SHARED_DIR (the block's \$S, \$H)"
    finish
fi
if ! have_tmux; then
    skip readme_usage_lines_run_as_written "tmux not installed"
    finish
fi
CLONE=$ROOT/$OUT/clone
mkdir -p "$CLONE"
ln -sfn "$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")" "$CLONE/rastty"
ln -sfn "$ROOT/assets" "$CLONE/assets"
ln -sfn "$(cd "$SHARED_DIR" && pwd)" "$ROOT/$OUT/shared"

# one line N: how it ran, in $OUT/line-N.out
run_line() {
    local n=$1 line=$2 out=$ROOT/$OUT/line-$1.out s=view$1 rc
    local words; read -ra words <<< "$line"
    case "${words[0]}" in
    make)
        make -n -C "$ROOT" "${words[1]}" > "$out" 2>&1 ;;
    ./rastty)
        if [[ ${words[1]:-} =~ ^(render|dump|ansi2ppm|bench)$ ]]; then
            if [[ $line == *"bench --chart"* ]]; then
                (cd "$CLONE" && timeout $((20 * SLOW)) bash -c "$line") > "$out" 2>&1
                rc=$?; [ $rc -eq 0 ] || [ $rc -eq 124 ]
            else
                (cd "$CLONE" && timeout $((300 * SLOW)) bash -c "$line") > "$out" 2>&1
            fi
        else # the viewer
            rm -f "$ROOT/$OUT/$s.exit"
            tm new-session -d -s $s -x 100 -y 30 -c "$CLONE" \
                "env S=$(printf '%q' "${S:-}") H=$(printf '%q' "${H:-}") bash -c $(printf '%q' "$line"$'\n'"echo \$? > $ROOT/$OUT/$s.exit"); sleep 60" || return 1
            wait_for 60 hud_has $s " fps" || { tm capture-pane -t $s -p | grep -v '^$' | tail -3; return 1; }
            tm send-keys -t $s q
            wait_for 20 test -f "$ROOT/$OUT/$s.exit" || { echo "q did not quit"; return 1; }
            tm kill-session -t $s
            [ "$(cat "$ROOT/$OUT/$s.exit")" = 0 ]
        fi ;;
    *)
        echo "a line of a kind this test does not know: $line"; return 1 ;;
    esac
}
usage_lines() {
    local n=0 line ran=0
    export S H
    while IFS= read -r line; do
        n=$((n + 1))
        [[ -z $line || $line == \#* ]] && continue
        if [[ $line =~ ^[A-Z]+= ]]; then # S=... H=...: for the lines after it
            eval "${line%%#*}"; continue
        fi
        run_line $n "$line" || { echo "line $n failed: $line"; tail -5 "$ROOT/$OUT/line-$n.out" 2>/dev/null; return 1; }
        ran=$((ran + 1))
    done < <(block)
    echo "$ran lines ran"
    [ $ran -ge 10 ]
}
check readme_usage_lines_run_as_written usage_lines

finish
