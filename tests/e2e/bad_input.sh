#!/usr/bin/env bash
# bad_input.sh: every bad input gets one clear line naming the file (and line), exit status 2,
# no crash, and never raw bytes from the input file on the terminal.
source "$(dirname "$0")/lib/common.sh"

# expect STATUS PATTERN CMD...: exit status STATUS, stderr one line matching PATTERN, no
# control bytes in it (apart from the newline), nothing on stdout
expect() {
    local want=$1 pat=$2; shift 2
    local err=$OUT/err.txt out=$OUT/out.txt rc
    "$@" > "$out" 2> "$err"; rc=$?
    local lines; lines=$(wc -l < "$err")
    echo "exit $rc, stderr: $(cat "$err")"
    [ "$rc" -eq "$want" ] || { echo "want exit $want"; return 1; }
    [ "$lines" -eq 1 ] || { echo "want exactly one line on stderr, got $lines"; return 1; }
    grep -qE -- "$pat" "$err" || { echo "stderr does not match /$pat/"; return 1; }
    if LC_ALL=C grep -q $'[\x01-\x09\x0b-\x1f\x7f]' "$err"; then echo "control bytes in stderr"; return 1; fi
    [ ! -s "$out" ] || { echo "unexpected stdout"; return 1; }
}

D=$OUT/files
mkdir -p $D
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' > $D/bad_index.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 x 0\nf 1 2 3\n' > $D/bad_number.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl \033[31mred\033]0;owned\007\nf 1 2 \033[2J3\n' > $D/control.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib nothere.mtl\nf 1 2 3\n' > $D/missing_mtl.obj
printf 'this is not an image\n' > $D/fake.png
printf 'model %s/assets/cube.obj\nlight 1 1 1\nbackground 0 0 nine\n' "$PWD" > $D/bad.rsc
head -c 4096 /dev/urandom > $D/random.obj

check malformed_obj_index expect 2 "bad_index.obj:4:" "$BIN" render $D/bad_index.obj --out $OUT/x.png
check malformed_obj_number expect 2 "bad_number.obj:4:" "$BIN" render $D/bad_number.obj --out $OUT/x.png
check control_bytes_never_echoed expect 2 "control.obj:6:" "$BIN" render $D/control.obj --out $OUT/x.png
# a material's missing file is a warning naming the line; the model draws (exit 0)
check missing_mtllib_is_a_warning expect 0 "^warning: .*missing_mtl.obj:4: cannot open material library '.*nothere.mtl'" "$BIN" render $D/missing_mtl.obj --out $OUT/x.png
printf 'newmtl red\nKd 1 0 0\nmap_Kd gone.png\n' > $D/gone.mtl
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nmtllib gone.mtl\nusemtl red\nf 1/1 2/1 3/1\n' > $D/gone.obj
missing_map_kd() {
    expect 0 "^warning: .*gone.mtl:3: cannot open texture '.*gone.png': No such file or directory; drawn without it$" \
        "$BIN" render $D/gone.obj --eye 0.3,0.3,1 --shade unlit --out $OUT/gone.ppm || return 1
    # drawn with the material's Kd: red pixels
    local px; px=$(ppmstat $OUT/gone.ppm 0,0,0); echo "ppmstat: $px"; set -- $px
    [ "$3" -gt 100 ]
}
check missing_map_kd_draws_with_kd missing_map_kd
# files named on the command line stay errors
check missing_texture_flag expect 2 "nothere.png: cannot open texture: No such file" "$BIN" render assets/cube.obj --texture $D/nothere.png --out $OUT/x.png
check not_a_model expect 2 "checker2x2.png: not a model \(PNG image\)" "$BIN" render tests/data/obj/checker2x2.png --out $OUT/x.png
check missing_model_file expect 2 "nope.obj" "$BIN" render $D/nope.obj --out $OUT/x.png
check corrupt_texture expect 2 "fake.png" "$BIN" render assets/cube.obj --texture $D/fake.png --out $OUT/x.png
check scene_file_error_names_line expect 2 "bad.rsc:3:" "$BIN" render $D/bad.rsc --out $OUT/x.png
check random_bytes_obj expect 2 "random.obj" "$BIN" render $D/random.obj --out $OUT/x.png
check bad_flag_value expect 2 "--fov" "$BIN" render assets/cube.obj --fov abc --out $OUT/x.png
check unknown_flag expect 2 "unknown option '--frobnicate' \\(see" "$BIN" render assets/cube.obj --frobnicate --out $OUT/x.png
check unknown_flag_suggests_the_nearest expect 2 "unknown option '--fames' \\(did you mean --frames\\?" "$BIN" dump assets/cube.obj --fames 3
check unknown_subcommand_suggests_the_nearest expect 2 "unknown subcommand 'rendr' \\(did you mean render\\?" "$BIN" rendr assets/cube.obj --out $OUT/x.png
check bad_light_value expect 2 "--light: .*camera" "$BIN" render assets/cube.obj --light cam --out $OUT/x.png
check bad_sky_value expect 2 "--sky: expected procedural" "$BIN" render assets/cube.obj --sky cloudy --out $OUT/x.png
check zero_size expect 2 "--size" "$BIN" render assets/cube.obj --size 0x0 --out $OUT/x.png
bad_lod() { # every malformed --lod is one line naming the flag and the value, exit 2
    for v in 0 1.5 -0.25 fast nan inf auto: auto:0 auto:-1 auto:x auto:1e9; do
        expect 2 "^rastty: --lod: expected off, auto, auto:PX .*got '$v'$" \
            "$BIN" render assets/teapot.obj --lod "$v" --out $OUT/x.png || { echo "--lod $v"; return 1; }
    done
    expect 2 "^rastty: --lod: expected" "$BIN" dump assets/teapot.obj --lod 2 --out $OUT/x.ans &&
        expect 2 "^rastty: --lod: expected" "$BIN" --lod half assets/teapot.obj &&
        expect 2 "--lod does not apply" "$BIN" ansi2ppm x.ans --out $OUT/x.ppm --lod auto
}
check bad_lod_values bad_lod
check huge_size expect 2 "--size" "$BIN" render assets/cube.obj --size 9000x10 --out $OUT/x.png
check flag_for_other_subcommand expect 2 "does not apply" "$BIN" render assets/cube.obj --diff --out $OUT/x.png
check missing_out expect 2 "--out" "$BIN" render assets/cube.obj
check bad_output_extension expect 2 "\\.ppm or \\.png" "$BIN" render assets/cube.obj --out $OUT/x.jpg
check eye_equals_target expect 2 "differ" "$BIN" render assets/cube.obj --eye 0,0,0 --out $OUT/x.png
check bad_env_threads expect 2 "RASTTY_THREADS: expected a thread count" env RASTTY_THREADS=0 "$BIN" render assets/cube.obj --out $OUT/x.png
check bad_env_simd expect 2 "RASTTY_SIMD: expected auto, ref, sse2, avx2, avx2-4 or avx2-8" env RASTTY_SIMD=neon "$BIN" render assets/cube.obj --out $OUT/x.png
check dump_bad_camera_path expect 2 "path.txt:2:" sh -c "printf '0 0 3 0 0 0\nnot numbers\n' > $D/path.txt; exec $BIN dump assets/cube.obj --camera-path $D/path.txt --out $OUT/x.ans"
# (a letter is a text cell now, as in a capture's status line: a control byte is garbage)
check ansi2ppm_rejects_garbage expect 2 "byte 16: unexpected byte 0x01" sh -c "printf '\033[H\033[38;2;1;2;3m\001' > $D/g.ans; exec $BIN ansi2ppm $D/g.ans --out $OUT/x.ppm"
# valid but extreme: UVs of 1e38 overflow u*width to inf; must render, not hit undefined
# behaviour (the sanitizer run checks float-to-int conversions)
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 1e38 1e38\nvt 1e38 0\nvt 0 1e38\nf 1/1 2/2 3/3\n' > $D/huge_uv.obj
huge_uv() { "$BIN" render $D/huge_uv.obj --texture assets/checker.png --filter bilinear --out $OUT/huge.ppm; }
check huge_uvs_render_cleanly huge_uv
# the --out path is quoted like any other: an ESC in a file name never reaches stderr
check out_path_escaped expect 2 "x\?\[31m.jpg: use a .ppm or .png" "$BIN" render assets/cube.obj --out $'x\e[31m.jpg'
check out_path_escaped_on_create expect 1 "/nonexistent/\?\]0;x\?.png: cannot create" "$BIN" render assets/cube.obj --out $'/nonexistent/\e]0;x\a.png'
# --help and --version report a failed write (exit 1), not success
help_full() {
    "$BIN" --help > /dev/full 2> $OUT/help.err; local rc=$?
    "$BIN" --version > /dev/full 2>> $OUT/help.err; local rc2=$?
    echo "exit $rc $rc2: $(cat $OUT/help.err)"
    [ $rc -eq 1 ] && [ $rc2 -eq 1 ] && grep -q "write failed: No space left on device" $OUT/help.err
}
check help_to_a_full_disk_fails help_full
check viewer_bad_file_before_terminal expect 2 "bad_index.obj:4:" "$BIN" $D/bad_index.obj

# An output named like an input (or like another output) is refused, exit 2, and the input
# is untouched (issue 25: each of these destroyed it, exit 0). Compared by device and inode:
# a symlink or a hard link to the input is the input.
same_file() {
    local d=$OUT/same; rm -rf $d; mkdir -p $d
    cp assets/cube.obj $d/m.obj; cp assets/checker.png $d/t.png
    printf '0 0 3 0 0 0\n' > $d/p.txt
    ln -s m.obj $d/link.obj; ln $d/m.obj $d/hard.obj
    cp $d/m.obj $d/m.orig; cp $d/t.png $d/t.orig; cp $d/p.txt $d/p.orig
    expect 2 "--out .*m.obj.* is the same file as the model" "$BIN" dump $d/m.obj --out $d/m.obj || return 1
    expect 2 "same file as the model" "$BIN" render $d/m.obj --out $d/link.obj || return 1
    expect 2 "same file as the model" "$BIN" render $d/m.obj --out $d/hard.obj || return 1
    expect 2 "same file as the --camera-path" "$BIN" dump $d/m.obj --camera-path $d/p.txt --out $d/p.txt || return 1
    expect 2 "same file as the --texture" "$BIN" render $d/m.obj --texture $d/t.png --out $d/t.png || return 1
    expect 2 "same file as the input" "$BIN" ansi2ppm $d/p.txt --out $d/./p.txt || return 1
    expect 2 "--out .*x.ppm.* and --depth-out .*x.ppm.* are the same file" "$BIN" render $d/m.obj --out $d/x.ppm --depth-out $d/x.ppm || return 1
    [ ! -e $d/x.ppm ] || { echo "x.ppm written"; return 1; }
    cmp $d/m.obj $d/m.orig && cmp $d/t.png $d/t.orig && cmp $d/p.txt $d/p.orig || { echo "an input changed"; return 1; }
    [ -L $d/link.obj ] || { echo "the symlink was replaced"; return 1; }
    "$BIN" render $d/m.obj --out $d/ok.ppm --depth-out $d/ok.pfm || { echo "distinct outputs refused"; return 1; }
}
check an_output_that_is_an_input_is_refused same_file

finish
