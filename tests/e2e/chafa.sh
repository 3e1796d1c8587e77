#!/usr/bin/env bash
# chafa.sh (issue 9): rastty's cell fitting against chafa's, the reference tool for pictures
# in terminals, on the same framebuffer with the same symbols (tests/e2e/lib/glyphcmp.sh):
# with half blocks rastty is at least as accurate and writes fewer bytes; the other glyph
# sets are reported (tests/bench_glyphs.sh prints the table).
source "$(dirname "$0")/lib/common.sh"
source tests/e2e/lib/glyphcmp.sh

HEAD=$SHARED/african_head/african_head.obj
if ! command -v chafa >/dev/null 2>&1; then
    skip half_blocks_beat_chafa "chafa not installed (Debian: apt-get install chafa)"
    finish
fi
if [ ! -f "$HEAD" ]; then
    skip half_blocks_beat_chafa "no shared models at $SHARED"
    finish
fi

# "r_psnr r_bytes c_psnr c_bytes": at least as accurate ("inf" = exact), fewer bytes
no_worse() {
    local line; line=$(glyphcmp "$HEAD" 80 48 "$1") || return 1
    echo "$line  (set rastty_psnr rastty_bytes rastty_ms chafa_psnr chafa_bytes chafa_ms)"
    set -- $line
    awk -v r="$2" -v c="$5" 'BEGIN { r = r == "inf" ? 1e9 : r; c = c == "inf" ? 1e9 : c; exit !(r >= c) }' &&
        [ "$3" -lt "$6" ]
}
check half_blocks_beat_chafa no_worse half
for g in quadrant sextant braille ascii; do
    echo "  $(glyphcmp "$HEAD" 80 48 $g)"
done
finish
