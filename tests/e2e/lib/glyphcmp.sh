# tests/e2e/lib/glyphcmp.sh: rastty's cell fitting against chafa's (sourced, not run; needs
# BIN, OUT and build/e2e/psnr). One glyph set at a time:
#   glyphcmp MODEL COLS ROWS SET   prints "SET r_psnr r_bytes r_ms c_psnr c_bytes c_ms"
# rastty dumps MODEL (--sky procedural, truecolor) with --glyphs SET and keeps the
# framebuffer at the set's sub-cell grid (--ppm-dir); chafa draws that very framebuffer on
# COLS x ROWS cells with the same symbols (-c full, --dither none, -w 9: its most careful
# fitting; braille --fg-only, as ours is), given it scaled up by whole pixels to 8x8 pixels
# a cell, chafa's own cell grid (given the small picture, chafa's smooth resampling blurs it:
# half blocks 33 dB where the same picture at 8x8 a cell is exact). Both outputs are decoded
# on the set's grid by `rastty ansi2ppm --glyphs SET` and compared with the framebuffer (PSNR,
# dB). r_ms: rastty's encode time (dump --stats); c_ms: chafa's whole run (it loads the
# picture too).
PSNR=build/e2e/psnr
if [ ! -x $PSNR ] || [ tests/e2e/lib/psnr.c -nt $PSNR ]; then
    mkdir -p build/e2e && cc -O2 -std=c11 -o $PSNR.$$ tests/e2e/lib/psnr.c -lm && mv -f $PSNR.$$ $PSNR
fi

chafa_symbols() {
    case $1 in
    half) echo "space+vhalf";;            # chafa's vhalf: U+2580, U+2584
    quadrant) echo "space+quad+vhalf+hhalf";;
    sextant) echo "space+sextant+hhalf";;  # chafa's hhalf: U+258C, U+2590
    braille) echo "braille";;
    ascii) echo "space";;                  # colour modes: a space on the cell's colour
    esac
}

glyphcmp() {
    local model=$1 cols=$2 rows=$3 g=$4 d=$OUT/cmp-$4
    rm -rf "$d" && mkdir -p "$d" || return 1
    "$BIN" dump "$model" --cols "$cols" --rows "$rows" --glyphs "$g" --colors truecolor \
        --sky procedural --ppm-dir "$d" --stats --out "$d/r.ans" 2> "$d/stats.txt" || return 1
    local rms; rms=$(sed -n 's/.* \([0-9.]*\) ms encode$/\1/p' "$d/stats.txt")
    local extra=; [ "$g" = braille ] && extra=--fg-only
    $PSNR --upscale $((8 * cols)) $((8 * rows)) "$d/frame-0000.ppm" "$d/big.ppm" || return 1
    local t0 t1
    t0=$(date +%s%N)
    chafa -f symbols --symbols "$(chafa_symbols "$g")" $extra -s "${cols}x$rows" --stretch \
        -c full --dither none -w 9 --animate off "$d/big.ppm" > "$d/c.ans" || return 1
    t1=$(date +%s%N)
    "$BIN" ansi2ppm "$d/r.ans" --glyphs "$g" --out "$d/r.ppm" &&
        "$BIN" ansi2ppm "$d/c.ans" --glyphs "$g" --out "$d/c.ppm" || return 1
    echo "$g $($PSNR "$d/r.ppm" "$d/frame-0000.ppm") $(wc -c < "$d/r.ans") $rms" \
        "$($PSNR "$d/c.ppm" "$d/frame-0000.ppm") $(wc -c < "$d/c.ans")" \
        "$(( (t1 - t0) / 1000000 ))"
}
