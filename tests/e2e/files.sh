#!/usr/bin/env bash
# files.sh: rastty and the files people point it at — special files are refused at once
# (never read forever, never blocked on), outputs are replaced only when complete, texture
# decoders that crashed or hung are gone, and STL, PLY and glTF models draw.
source "$(dirname "$0")/lib/common.sh"

D=$(cd "$OUT" && pwd)/files
mkdir -p "$D"
CUBE=$PWD/assets/cube.obj

# run CMD with a time limit: a regression that blocks or reads /dev/zero fails here, it does
# not hang the suite. Expect exit status WANT and stderr matching PATTERN.
quick() { # WANT PATTERN CMD...
    local want=$1 pat=$2; shift 2
    timeout $((10 * SLOW)) "$@" > "$OUT/out.txt" 2> "$OUT/err.txt"; local rc=$?
    echo "exit $rc, stderr: $(head -c 400 "$OUT/err.txt")"
    [ $rc -eq "$want" ] || { echo "want exit $want"; return 1; }
    if [ "$pat" = - ]; then [ ! -s "$OUT/err.txt" ] || return 1
    else grep -qE -- "$pat" "$OUT/err.txt" || { echo "stderr does not match /$pat/"; return 1; }; fi
    ! LC_ALL=C grep -q $'[\x01-\x09\x0b-\x1f\x7f]' "$OUT/err.txt"
}

rm -f "$D/fifo"; mkfifo "$D/fifo"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib /dev/zero\nf 1 2 3\n' > "$D/zero_mtl.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib fifo\nf 1 2 3\n' > "$D/fifo_mtl.obj"
printf 'newmtl m\nmap_Kd fifo\n' > "$D/fifo_tex.mtl"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nmtllib fifo_tex.mtl\nusemtl m\nf 1/1 2/1 3/1\n' > "$D/fifo_tex.obj"
printf 'model /dev/zero\n' > "$D/zero_model.rsc"
printf 'model %s\nsky fifo fifo fifo fifo fifo fifo\n' "$CUBE" > "$D/fifo_sky.rsc"

# issue 12, defect 3: special files
check mtllib_dev_zero_is_refused quick 0 "zero_mtl.obj:4: cannot open material library '/dev/zero': a device, not a regular file" "$BIN" render "$D/zero_mtl.obj" --out "$OUT/x.png"
check mtllib_fifo_is_refused quick 0 "fifo_mtl.obj:4: cannot open material library '.*fifo': a FIFO, not a regular file" "$BIN" render "$D/fifo_mtl.obj" --out "$OUT/x.png"
check map_kd_fifo_is_refused quick 0 "fifo_tex.mtl:2: cannot open texture '.*fifo': a FIFO, not a regular file" "$BIN" render "$D/fifo_tex.obj" --out "$OUT/x.png"
check scene_model_dev_zero quick 2 "zero_model.rsc:1: /dev/zero: cannot read: a device, not a regular file" "$BIN" render "$D/zero_model.rsc" --out "$OUT/x.png"
check sky_face_fifo quick 2 "fifo_sky.rsc:2: .*fifo: cannot open texture: a FIFO, not a regular file" "$BIN" render "$D/fifo_sky.rsc" --out "$OUT/x.png"
check model_fifo quick 2 "fifo: cannot read: a FIFO" "$BIN" render "$D/fifo" --out "$OUT/x.png"
check texture_flag_dev_urandom quick 2 "/dev/urandom: cannot open texture: a device" "$BIN" render "$CUBE" --texture /dev/urandom --out "$OUT/x.png"
check ansi2ppm_dev_zero quick 2 "/dev/zero: cannot read: a device, not a regular file" "$BIN" ansi2ppm /dev/zero --out "$OUT/x.ppm"
check camera_path_dev_zero quick 2 "/dev/zero: cannot open camera path: a device" "$BIN" dump "$CUBE" --camera-path /dev/zero --out "$OUT/x.ans"

# issue 12, defect 5: outputs are replaced only when complete (a full disk: RLIMIT_FSIZE)
full_disk() { # FILE CMD...: FILE keeps its old bytes when CMD hits the size limit
    local file=$1; shift
    printf 'the old contents\n' > "$file"
    ( trap '' XFSZ; ulimit -f 4; exec "$@" ) > /dev/null 2> "$OUT/err.txt"; local rc=$?
    echo "exit $rc, stderr: $(cat "$OUT/err.txt")"
    [ $rc -eq 1 ] || { echo "want exit 1"; return 1; }
    grep -q "write failed: File too large" "$OUT/err.txt" || return 1
    [ "$(cat "$file")" = "the old contents" ] || { echo "old file replaced"; return 1; }
    local left; left=$(ls -A "$(dirname "$file")" | grep -c "^\.$(basename "$file")\." || true)
    [ "$left" -eq 0 ] || { echo "temporary file left behind"; return 1; }
}
mkdir -p "$D/out"
check render_out_full_disk full_disk "$D/out/old.ppm" "$BIN" render "$CUBE" --size 640x480 --out "$D/out/old.ppm"
check render_png_full_disk full_disk "$D/out/old.png" "$BIN" render "$CUBE" --size 640x480 --out "$D/out/old.png"
check depth_out_full_disk full_disk "$D/out/old.pfm" "$BIN" render "$CUBE" --size 160x120 --out "$D/out/ok.png" --depth-out "$D/out/old.pfm"
check dump_out_full_disk full_disk "$D/out/old.ans" "$BIN" dump "$CUBE" --cols 200 --rows 60 --colors truecolor --out "$D/out/old.ans"
mkdir -p "$D/frames"
check ppm_dir_full_disk full_disk "$D/frames/frame-0000.ppm" "$BIN" dump "$CUBE" --cols 200 --rows 60 --ppm-dir "$D/frames"
atomic_ok() {
    "$BIN" render "$CUBE" --out "$D/out/new.png" && [ -s "$D/out/new.png" ] &&
        [ -z "$(ls -A "$D/out" | grep '^\.new\.png\.')" ]
}
check successful_write_leaves_no_temp_file atomic_ok

# issue 12, defects 1 and 2: textures that crashed or hung stb_image
/usr/bin/python3 -c "
import sys
w = h = 1024
sys.stdout.buffer.write(b'P5 %d %d 65535\n' % (w, h) + bytes(range(256)) * (w * h * 2 // 256))" > "$D/x16.pgm"
check pgm_16_bit_texture quick 0 - "$BIN" render "$CUBE" --texture "$D/x16.pgm" --out "$OUT/x.png"
if [ -f "$SHARED/sky_hdr/venice_sunset_1k.hdr" ]; then
    hdr_cuts() {
        for n in 200 1000 10000 100000 500000; do
            head -c $n "$SHARED/sky_hdr/venice_sunset_1k.hdr" > "$D/cut.hdr"
            quick 2 "cut.hdr: (truncated HDR|bad or truncated HDR scanline)" "$BIN" render "$CUBE" --texture "$D/cut.hdr" --out "$OUT/x.png" || return 1
        done
    }
    check truncated_hdr_fails_at_once hdr_cuts
else
    skip truncated_hdr_fails_at_once "no shared models at $SHARED"
fi

# issue 12: models in other formats draw, and what is no model says what it is
draws() { # FILE: renders, and the picture has a model in it
    "$BIN" render "$1" --frame --size 160x120 --out "$OUT/m.ppm" 2> "$OUT/err.txt" || { cat "$OUT/err.txt"; return 1; }
    local s; s=$(ppmstat "$OUT/m.ppm" 0,0,0); echo "$1: $s"; set -- $s
    [ "$3" -gt 1500 ]
}
C=tests/fuzz/corpus
check stl_ascii_draws draws $C/stl/square_ascii.stl
check stl_binary_draws draws $C/stl/square_binary.stl
check ply_binary_draws draws $C/ply/quad_le.ply
check gltf_draws draws $C/import/tri.gltf
check glb_draws draws $C/import/tri.glb
check collada_draws draws $C/import/tri.dae
# a one-byte change to a COLLADA file that crashes assimp (found by fuzz_import): the
# importer runs in a child process, so it is one error line, not a dead rastty
# (under ASan its handler turns the SIGSEGV into an abort: signal 6)
segv=11; [ -n "${RASTTY_ASAN:-}" ] && segv=6
check assimp_crash_is_an_error quick 2 "assimp_segv.dae: the importer crashed on this file \\(killed by signal $segv\\)" "$BIN" render tests/data/models/assimp_segv.dae --out "$OUT/x.png"
check jpeg_is_not_a_model quick 2 "stb_jpeg_ub.jpg: not a model \(JPEG image\)" "$BIN" render tests/data/tex/stb_jpeg_ub.jpg --out "$OUT/x.png"

finish
