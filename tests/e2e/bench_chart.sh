#!/usr/bin/env bash
# bench_chart.sh: `rastty bench` (the viewer frame, the encodings), `--chart` and `--sweep NAME`
# from the command line, at tiny sizes (the full chart is a benchmark: `make chart`). The CSV
# headers are exact, every row is there, methods that draw the same pixels get the same error,
# the ideal's own methods score infinity, the SVG is well formed, the terminal chart comes out
# through the encoder, and bad combinations of flags are one-line errors with exit status 2.
source "$(dirname "$0")/lib/common.sh"

CSV=$OUT/chart.csv SVG=$OUT/chart.svg
# no shared models here: the built-in scenes alone (demo, ground, sphere)
chart() {
    RASTTY_SHARED=$OUT/none "$BIN" bench --chart --size 48x32 --repeat 1 --csv $CSV \
        --svg $SVG > $OUT/chart.txt 2> $OUT/chart.err
}
check chart_runs chart
check chart_says_which_scenes_it_skipped grep -q "no shared models: head, car, empire, bunny skipped" $OUT/chart.err
csv_header() { # the issue's columns first; part 3's follow (lod, then shimmer last)
    local h; h=$(head -n 1 $CSV)
    [ "${h%%,bytes*},bytes" = "scene,size,raster,persp,depth,filter,ssaa,ms,psnr_db,frac_gt8,bytes" ] &&
        [ "${h##*,bytes,}" = lod,shimmer,glyphs,encode_ms ]
}
check chart_csv_header_is_exact csv_header
# per scene: the default, every other value of every axis alone (2+4+3+2+3+1 = 15), and the
# fastest combination unless a row has it already (the most accurate is the ideal: ssaa 8
# with trilinear, not among the single-axis rows)
rows() {
    for s in demo ground sphere; do
        local n; n=$(grep "^$s,48x32," $CSV | grep -c ",half,$")
        [ "$n" -ge 16 ] && [ "$n" -le 17 ] || { echo "$s: $n rows"; return 1; }
    done
}
check chart_has_every_method_of_every_scene rows
# glyph rows (no head here: the demo): one per glyph set with its encode time, and the half
# block row is the default row (truecolor half blocks are lossless: same error, same bytes)
glyph_rows() {
    local sets; sets=$(awk -F, '$15 != "" && NR > 1 { print $1 "/" $14 }' $CSV | tr '\n' ' ')
    echo "glyph rows: $sets"
    [ "$sets" = "demo/half demo/quadrant demo/sextant demo/braille demo/ascii " ] || return 1
    local def half
    def=$(awk -F, '$1 == "demo" && $3 == "edge" && $4 == "correct" && $5 == "z" && $6 == "trilinear" && $7 == 1 && $12 == "off" && $15 == "" { print $9, $11 }' $CSV)
    half=$(awk -F, '$1 == "demo" && $14 == "half" && $15 != "" { print $9, $11 }' $CSV)
    echo "default: $def, glyphs half: $half"
    [ -n "$def" ] && [ "$def" = "$half" ]
}
check chart_glyph_rows glyph_rows
same_as_default() { # methods that draw the same pixels as the default score the same
    awk -F, 'NR > 1 && $3 == "edge" && $4 == "correct" && $5 == "z" && $6 == "trilinear" && $7 == 1 && $12 == "off" && $15 == "" { d[$1] = $9 "," $10 "," $11 }
             NR > 1 && $4 == "correct" && $6 == "trilinear" && $7 == 1 && $12 == "off" && $15 == "" && ($3 != "edge" || $5 == "w" || $5 == "rz") { s[$1 "/" $3 "/" $5] = $1 }
             END { for (k in s) { split(k, p, "/"); print k, p[1] } }' $CSV > $OUT/same.txt
    [ -s $OUT/same.txt ] || return 1
    while read -r key scene; do
        IFS=/ read -r sc r dm <<< "$key"
        local want got
        want=$(awk -F, -v s=$sc 'NR > 1 && $1 == s && $3 == "edge" && $4 == "correct" && $5 == "z" && $6 == "trilinear" && $7 == 1 && $12 == "off" && $15 == "" { print $9 "," $10 "," $11 }' $CSV)
        got=$(awk -F, -v s=$sc -v r=$r -v d=$dm 'NR > 1 && $1 == s && $3 == r && $4 == "correct" && $5 == d && $6 == "trilinear" && $7 == 1 && $12 == "off" && $15 == "" { print $9 "," $10 "," $11 }' $CSV)
        [ "$want" = "$got" ] || { echo "$key: $got, default $want"; return 1; }
    done < $OUT/same.txt
}
check rasterizers_and_w_rz_score_as_the_default same_as_default
ideal_is_exact() { # correct, trilinear, ssaa 8 with the default raster and depth: the ideal
    local n; n=$(awk -F, '$3 == "edge" && $4 == "correct" && $5 == "z" && $6 == "trilinear" && $7 == 8 && $12 == "off" && $15 == "" && $9 == "inf" && $10 == 0' $CSV | wc -l)
    [ "$n" -eq 3 ]
}
check ideal_methods_score_infinity ideal_is_exact
more_samples_more_accurate() { # on every scene, PSNR rises with --ssaa
    for s in demo ground sphere; do
        awk -F, -v s=$s '$1 == s && $3 == "edge" && $4 == "correct" && $5 == "z" && $6 == "trilinear" && $12 == "off" && $15 == "" { p[$7] = $9 }
                         END { if (!(p[1] < p[2] && p[2] < p[4] && p[4] < p[8])) { print s, p[1], p[2], p[4], p[8]; exit 1 } }' $CSV || return 1
    done
}
check ssaa_raises_psnr more_samples_more_accurate
svg_ok() {
    /usr/bin/python3 -c "import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])" $SVG &&
        grep -q "Pareto front" $SVG && grep -q "48x32: demo, ground, sphere" $SVG
}
check chart_svg_is_well_formed svg_ok
check chart_table_on_stdout grep -q "most accurate" $OUT/chart.txt

terminal_chart() { # without --svg: the chart drawn with the half-block encoder, then the table
    RASTTY_SHARED=$OUT/none "$BIN" bench --chart --size 32x24 --repeat 1 --csv $OUT/t.csv \
        > $OUT/term.ans 2>/dev/null || return 1
    grep -q $'\033\\[2J' $OUT/term.ans && grep -q "▀\|▄" $OUT/term.ans &&
        grep -q "scene   size  *raster" $OUT/term.ans
}
check chart_in_the_terminal terminal_chart

sweep_csv() { # sweep NAME: header, one row per step and method, a failure point stated
    local s=$1
    "$BIN" bench --sweep "$s" --size 48x32 --csv $OUT/$s.csv --svg $OUT/$s.svg > $OUT/$s.txt || return 1
    [ "$(head -n 1 $OUT/$s.csv)" = "sweep,param,method,error,nan,failed" ] || return 1
    grep -q "^fails: " $OUT/$s.txt && grep -q "^failure point" $OUT/$s.txt &&
        /usr/bin/python3 -c "import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])" $OUT/$s.svg
}
for s in grazing depthrange magnitude sliver nearplane minification; do
    check sweep_${s}_table_csv_svg sweep_csv $s
done
z16_fails() { grep -q "^failure point z16 *177.828 (theory: 177.828)" $OUT/depthrange.txt; }
check depthrange_z16_fails_where_theory_says z16_fails

# the plain bench: the viewer's frame first (render + encode: positive times, the whole frame
# at least either part), then the table of encodings (lossless ones decode to the exact frame)
bench_scene() {
    "$BIN" bench assets/cube.obj --cols 40 --rows 12 --frames 4 > $OUT/scene.txt || return 1
    awk '/cube.obj: viewer frame .*median/ { f = $0; sub(/.*median /, "", f); split(f, w, " ")
                                             r = w[4]; e = w[7]; sub(/\)/, "", e)
                                             if (r > 0 && e > 0 && w[1] >= r && w[1] >= e) ok = 1 }
         /^  diff truecolor .* inf +inf +0$/ { lossless = 1 }
         END { exit !(ok && lossless) }' $OUT/scene.txt || { cat $OUT/scene.txt; return 1; }
}
check bench_viewer_frame_then_encodings bench_scene

expect2() { # STATUS 2, one line on stderr matching PATTERN
    local pat=$1; shift
    "$@" > $OUT/x.out 2> $OUT/x.err; local rc=$?
    [ $rc -eq 2 ] && [ "$(wc -l < $OUT/x.err)" -eq 1 ] && grep -qE -- "$pat" $OUT/x.err ||
        { echo "exit $rc: $(cat $OUT/x.err)"; return 1; }
}
check chart_and_sweep_exclude_each_other expect2 "separate" "$BIN" bench --chart --sweep grazing
check unknown_sweep expect2 "--sweep: expected grazing" "$BIN" bench --sweep wobble
check csv_needs_chart_or_sweep expect2 "go with" "$BIN" bench assets/demo.rsc --csv $OUT/x.csv
check chart_takes_no_models expect2 "own scene set" "$BIN" bench --chart assets/cube.obj
check chart_size_fits_the_ideal expect2 "--ssaa 8 at 1100x96" "$BIN" bench --chart --size 1100x96
check ssaa_8_too_big_to_render expect2 "needs a 9600x768 framebuffer" "$BIN" render assets/cube.obj --size 1200x96 --ssaa 8 --out $OUT/x.png
check ssaa_bad_value expect2 "--ssaa: expected 1, 2, 4 or 8" "$BIN" render assets/cube.obj --ssaa 3 --out $OUT/x.png
finish
