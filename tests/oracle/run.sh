#!/usr/bin/env bash
# tests/oracle/run.sh: rastty against an independent reference renderer (Mesa via OSMesa).
#
#   tests/oracle/run.sh [--calibrate|--calibrate-clip] [--rastty PATH] [--only S] [--list N]
#
# Every scene of tests/oracle/scenes.txt is drawn by `rastty render` and by build/oracle/glref
# (Mesa llvmpipe unless GALLIUM_DRIVER says otherwise) and the two are compared by
# build/oracle/compare, one line per scene; rastty also draws each scene with --raster
# scanline and --raster tiled, which must write the same bytes (colour and depth) as the
# default edge rasterizer, then "N passed, N failed, N skipped"; exit 1 when a
# scene failed. Builds nothing: `make oracle-build` (tests/oracle/oracle.mk) makes glref and
# compare, the top-level Makefile makes rastty. Outputs go to build/oracle/out/NAME.*; a failing
# scene leaves NAME.diff.png there (red: only rastty covers, cyan: only Mesa covers, yellow:
# colour differs by more than 8, blue: by 1..8).
#
#   --calibrate   instead of rastty, compare Mesa softpipe (as the tested image) with Mesa
#                 llvmpipe: how far two conforming GL rasterizers differ on the same scenes.
#   --calibrate-clip  compare glref --gl-clip (float MVP in the shader, Mesa's float clipper)
#                 with glref's default (clip coordinates and frustum clipping in double).
#   --rastty P    the binary to test (default ./rastty, or $RASTTY)
#   --only S      run only scenes whose name contains S
#   --list N      print up to N mismatching pixels per scene (stderr)
# Environment: RASTTY_SHARED overrides ../shared (the shared models live in its models/);
# ORACLE_JOBS scenes run at a time (default one per core), their lines printed in order.
set -u

root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root" || exit 2

mode=rastty
rastty=${RASTTY:-./rastty}
only=
list=0
while [ $# -gt 0 ]; do
    case $1 in
    --calibrate) mode=calibrate ;;
    --calibrate-clip) mode=calibrate-clip ;;
    --rastty) rastty=$2; shift ;;
    --only) only=$2; shift ;;
    --list) list=$2; shift ;;
    --asan) ;; # accepted for tests/run.sh; the binary comes from --rastty
    *) echo "usage: tests/oracle/run.sh [--calibrate|--calibrate-clip] [--rastty PATH] [--only S] [--list N]" >&2
       exit 2 ;;
    esac
    shift
done

scenes=tests/oracle/scenes.txt
out=build/oracle/out
gen=build/oracle/models
glref=build/oracle/glref
compare=build/oracle/compare
shared_root=${RASTTY_SHARED:-../shared}
shared=$shared_root/models

# scene lines: name, checks, args (comments and blank lines dropped)
mapfile -t lines < <(grep -v '^[[:space:]]*\(#\|$\)' "$scenes")
total=0
for l in "${lines[@]}"; do
    read -r name _ <<<"$l"
    [[ -z $only || $name == *"$only"* ]] && total=$((total + 1))
done

passed=0 failed=0 skipped=0
summary() {
    echo "$passed passed, $failed failed, $skipped skipped"
    [ "$failed" -eq 0 ]
    exit $?
}

if ! { pkg-config --exists osmesa 2>/dev/null || [ -f /usr/include/GL/osmesa.h ]; }; then
    echo "oracle: OSMesa is not installed (Debian: apt-get install libosmesa6-dev); skipping all $total scenes"
    skipped=$total
    summary
fi
for b in "$glref" "$compare"; do
    if [ ! -x "$b" ]; then
        echo "oracle: $b is missing: run 'make oracle-build' first"
        failed=$total
        summary
    fi
done
if [ "$mode" = rastty ] && [ ! -x "$rastty" ]; then
    echo "oracle: $rastty does not exist yet (make rastty); skipping all $total scenes"
    skipped=$total
    summary
fi
have_gen=1
if ! /usr/bin/python3 tests/oracle/gen_models.py "$gen" 2>"$out.gen.err"; then
    mkdir -p "$out"
    echo "oracle: generating models failed ($(head -c 300 "$out.gen.err")); generated scenes are skipped"
    have_gen=0
fi
rm -f "$out.gen.err"
mkdir -p "$out"

if [ "$mode" = calibrate ]; then
    echo "oracle: calibration — Mesa softpipe (tested) against Mesa llvmpipe (reference)"
elif [ "$mode" = calibrate-clip ]; then
    echo "oracle: calibration — glref --gl-clip (tested) against glref (reference)"
else
    echo "oracle: $rastty render against Mesa ${GALLIUM_DRIVER:-llvmpipe}"
fi

# One scene (a line of scenes.txt): its lines on stdout; 0 passed, 1 failed, 2 skipped.
scene() {
    local l=$1
    local name checks args refargv testargv cmpflags refmodel sz i ref test raster_bad flags r
    read -r name checks args <<<"$l"
    if [[ $args == *'$SHARED'* && ! -d $shared ]]; then
        echo "$name SKIP (no shared models at $shared)"
        return 2
    fi
    if [[ $args == *'$GEN'* && $have_gen = 0 ]]; then
        echo "$name SKIP (generated models unavailable)"
        return 2
    fi
    args=${args//\$SHARED/$shared}
    args=${args//\$GEN/$gen}
    checks=${checks//\$GEN/$gen}
    read -r -a argv <<<"$args"
    # ref=MODEL: Mesa draws MODEL (the OBJ) where rastty draws the first argument (its STL
    # or glTF twin); everything else is the same
    refargv=("${argv[@]}") testargv=("${argv[@]}") cmpflags=()
    if [[ $checks == *ref=* ]]; then
        refmodel=${checks#*ref=}
        refargv=("${refmodel%%+*}" "${argv[@]:1}")
    fi
    # trilinear: rastty's level of detail is exact per pixel (the planes' derivatives), GL lets
    # llvmpipe approximate rho and log2. On a sharp checker seen at a grazing angle the two
    # differ by about a tenth of a level (the bias that best matches llvmpipe on
    # ground_floor_trilinear_160 is -0.1: 42.1 dB, against 41.0 unbiased), and a tenth of a
    # level between a sharp level and its grey average moves a pixel by up to ~30 levels in
    # the band where the texture fades. So such scenes get PSNR >= 38 dB and at most 8% of
    # the pixels off by more than 8 (measured: 41.0 dB, 4.6%); coverage keeps its bar.
    if [[ $checks == *trilinear* ]]; then
        cmpflags+=(--psnr-bar 38 --diff8-bar 0.08)
    fi
    # ideal: rastty draws its ideal image (--ssaa 8; the scene line gives --filter trilinear),
    # Mesa draws 8 times the size, and compare box-filters Mesa's picture down the same way
    if [[ $checks == *ideal* ]]; then
        for i in "${!refargv[@]}"; do
            if [ "${refargv[$i]}" = --size ]; then
                sz=${refargv[$((i + 1))]}
                refargv[$((i + 1))]=$((${sz%x*} * 8))x$((${sz#*x} * 8))
            fi
        done
        testargv+=(--ssaa 8)
        cmpflags+=(--reduce 8 --psnr-bar 40)
    fi
    ref=$out/$name.mesa test=$out/$name.rastty
    rm -f "$ref".* "$test".* "$out/$name.diff.png"
    if ! "$glref" "${refargv[@]}" --out "$ref.ppm" --depth-out "$ref.pfm" 2>"$ref.err"; then
        echo "$name FAIL (reference renderer: $(head -n 1 "$ref.err"))"
        return 1
    fi
    if [ "$mode" = calibrate ]; then
        test=$out/$name.softpipe
        if ! GALLIUM_DRIVER=softpipe "$glref" "${refargv[@]}" --out "$test.ppm" \
            --depth-out "$test.pfm" 2>"$test.err"; then
            echo "$name FAIL (softpipe: $(head -n 1 "$test.err"))"
            return 1
        fi
    elif [ "$mode" = calibrate-clip ]; then
        test=$out/$name.glclip
        if ! "$glref" "${refargv[@]}" --gl-clip --out "$test.ppm" --depth-out "$test.pfm" \
            2>"$test.err"; then
            echo "$name FAIL (glref --gl-clip: $(head -n 1 "$test.err"))"
            return 1
        fi
    elif ! "$rastty" render "${testargv[@]}" --out "$test.ppm" --depth-out "$test.pfm" \
        2>"$test.err" >/dev/null; then
        echo "$name FAIL (rastty render exited non-zero: $(head -n 1 "$test.err"))"
        return 1
    fi
    # every rasterizer must write the same bytes (colour and depth) as the default one
    raster_bad=
    if [ "$mode" = rastty ]; then
        for r in scanline tiled; do
            if ! "$rastty" render "${testargv[@]}" --raster "$r" --out "$test.$r.ppm" \
                --depth-out "$test.$r.pfm" 2>/dev/null >/dev/null ||
                ! cmp -s "$test.ppm" "$test.$r.ppm" || ! cmp -s "$test.pfm" "$test.$r.pfm"; then
                raster_bad="$raster_bad $r"
            else
                rm -f "$test.$r.ppm" "$test.$r.pfm"
            fi
        done
    fi
    flags=()
    [[ $checks == *magenta* ]] && flags+=(--magenta)
    [[ $checks == *exact* ]] && flags+=(--exact)
    [ "$mode" = rastty ] && flags+=("${cmpflags[@]}")
    local verdict=0
    if ! "$compare" --name "$name" "${flags[@]}" --list "$list" --diff "$out/$name.diff.png" \
        "$test.ppm" "$test.pfm" "$ref.ppm" "$ref.pfm" || [ -n "$raster_bad" ]; then
        [ -n "$raster_bad" ] && echo "$name FAIL (--raster$raster_bad: bytes differ from --raster edge: $test.*.ppm)"
        [ -f "$out/$name.diff.png" ] && echo "    diff image: $out/$name.diff.png"
        verdict=1
    fi
    rm -f "$ref.err" "$test.err"
    return $verdict
}

# The scenes run ORACLE_JOBS at a time (default one per core: each is a chain of short
# processes, and tests/run.sh runs other suites beside this one); their lines come out whole
# and in order, as each scene before them is done.
jobs=${ORACLE_JOBS:-$(nproc 2>/dev/null || echo 1)}
tmpd=$(mktemp -d "${TMPDIR:-/tmp}/rastty-oracle.XXXXXX")
trap 'rm -rf "$tmpd"' EXIT
todo=()
for l in "${lines[@]}"; do
    read -r name _ <<<"$l"
    [[ -n $only && $name != *"$only"* ]] || todo+=("$l")
done
next=0
flush() {
    while [ "$next" -lt "${#todo[@]}" ] && [ -e "$tmpd/$next.rc" ]; do
        cat "$tmpd/$next.out"
        case $(cat "$tmpd/$next.rc") in
        0) passed=$((passed + 1)) ;;
        2) skipped=$((skipped + 1)) ;;
        *) failed=$((failed + 1)) ;;
        esac
        next=$((next + 1))
    done
}
done_count() { local f=("$tmpd"/*.rc); [ -e "${f[0]}" ] && echo ${#f[@]} || echo 0; }
for i in "${!todo[@]}"; do
    while [ $((i - $(done_count))) -ge "$jobs" ]; do
        wait -n 2>/dev/null || sleep 0.1
        flush
    done
    ( scene "${todo[i]}" > "$tmpd/$i.out" 2>&1; echo $? > "$tmpd/$i.rc.new"; mv "$tmpd/$i.rc.new" "$tmpd/$i.rc" ) &
done
wait
flush
summary
