#!/usr/bin/env bash
# bench_glyphs.sh (issue 9): the glyph sets side by side, and against chafa given the same
# framebuffer with the same symbols (tests/e2e/lib/glyphcmp.sh says how). The textured head
# with the procedural sky on an 80x48 terminal: PSNR of the decoded terminal picture against
# the framebuffer at the set's sub-cell grid, bytes of the frame, encode ms (rastty: the
# encoder alone, from dump --stats; chafa: its whole run, loading the picture included).
set -u
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
OUT=build/bench/glyphs
mkdir -p $OUT
source tests/e2e/lib/glyphcmp.sh
HEAD=${RASTTY_SHARED:-../shared}/models/african_head/african_head.obj
echo "== glyph sets: the head, 80x48 cells, truecolor, against chafa (tests/bench_glyphs.sh)"
if [ ! -f "$HEAD" ]; then
    echo "   skipped: no shared models ($HEAD)"
    exit 0
fi
have_chafa=1
command -v chafa >/dev/null 2>&1 || { have_chafa=0; echo "   (chafa not installed: rastty alone)"; }
printf '   %-9s %9s %9s %8s   %9s %9s %8s\n' set "PSNR dB" bytes "enc ms" "chafa dB" "bytes" "ms (run)"
for g in half quadrant sextant braille ascii; do
    if [ $have_chafa = 1 ]; then
        set -- $(glyphcmp "$HEAD" 80 48 $g) || exit 1
    else
        d=$OUT/cmp-$g; mkdir -p $d
        "$BIN" dump "$HEAD" --cols 80 --rows 48 --glyphs $g --colors truecolor --sky procedural \
            --ppm-dir $d --stats --out $d/r.ans 2> $d/stats.txt || exit 1
        "$BIN" ansi2ppm $d/r.ans --glyphs $g --out $d/r.ppm || exit 1
        set -- $g $($PSNR $d/r.ppm $d/frame-0000.ppm) $(wc -c < $d/r.ans) \
            $(sed -n 's/.* \([0-9.]*\) ms encode$/\1/p' $d/stats.txt) - - -
    fi
    printf '   %-9s %9s %9s %8s   %9s %9s %8s\n' "$@"
done
