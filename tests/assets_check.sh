#!/usr/bin/env bash
# tests/assets_check.sh: validate the built-in assets written by assets/generate.c.
#   tests/assets_check.sh [ASSET_DIR [GENERATOR]]     (defaults: assets build/generate-assets;
#                                                      relative paths are from the repo root)
# Meshes (awk): exact v/vt/vn/triangle counts, indices in range, no degenerate triangles, every
#   directed edge used once (consistent winding), closed meshes watertight with the expected Euler
#   characteristic, positive volume (outward winding), unit normals that agree with the winding,
#   counter-clockwise UVs (unmirrored textures), sizes and placement, MTL and map_Kd present.
# Images: PNG, 8-bit RGB, power-of-two square sizes (od). With python3 (stdlib only): cubemap
#   faces agree along all 12 cube edges, the sky is up and the ground down on every side face,
#   and the sun sits at the posx/posy/posz corner.
# Determinism: with the generator, two fresh runs and ASSET_DIR are byte-identical.
# Ends with "N passed, N failed, N skipped"; exit status 1 when anything failed.
set -u
cd "$(dirname "$0")/.." || exit 1
dir=${1:-assets}
gen=${2:-build/generate-assets}
pass=0 fail=0 skip=0
ok()   { pass=$((pass + 1)); echo "ok   $1"; }
bad()  { fail=$((fail + 1)); echo "FAIL $1: $2"; }
skp()  { skip=$((skip + 1)); echo "skip $1: $2"; }
check() { # name condition-description awk-style-boolean-result(0/1)
    if [ "$3" = 1 ]; then ok "$1"; else bad "$1" "$2"; fi
}

# ---- OBJ analysis: one "key value" line per metric -------------------------------------------
obj_stats() {
    awk '
    function sq(x) { return x * x }
    /^v /  { nv++;  X[nv] = $2; Y[nv] = $3; Z[nv] = $4 }
    /^vt / { nvt++; U[nvt] = $2; W[nvt] = $3 }
    /^vn / { nvn++; NX[nvn] = $2; NY[nvn] = $3; NZ[nvn] = $4 }
    /^f /  {
        nf++
        if (NF != 4) nontri++
        for (k = 1; k <= 3; k++) {
            n = split($(k + 1), p, "/")
            if (n != 3 || p[2] == "" || p[3] == "") noattr++
            FV[nf, k] = p[1] + 0; FT[nf, k] = p[2] + 0; FN[nf, k] = p[3] + 0
        }
    }
    END {
        badidx = degen = dupdir = disagree = uvneg = 0; vol = 0; maxlen = 0
        xmin = ymin = zmin = 1e30; xmax = ymax = zmax = -1e30; rmin = 1e30; rmax = -1e30
        for (i = 1; i <= nv; i++) {
            if (X[i] < xmin) xmin = X[i]; if (X[i] > xmax) xmax = X[i]
            if (Y[i] < ymin) { ymin = Y[i]; ylo = i } if (Y[i] > ymax) { ymax = Y[i]; yhi = i }
            if (Z[i] < zmin) zmin = Z[i]; if (Z[i] > zmax) zmax = Z[i]
            r = sqrt(sq(X[i]) + sq(Y[i]) + sq(Z[i])); if (r < rmin) rmin = r; if (r > rmax) rmax = r
        }
        for (i = 1; i <= nvn; i++) {
            d = sqrt(sq(NX[i]) + sq(NY[i]) + sq(NZ[i])) - 1; if (d < 0) d = -d
            if (d > maxlen) maxlen = d
        }
        for (f = 1; f <= nf; f++) {
            for (k = 1; k <= 3; k++) {
                if (FV[f,k] < 1 || FV[f,k] > nv || FT[f,k] < 1 || FT[f,k] > nvt || \
                    FN[f,k] < 1 || FN[f,k] > nvn) { badidx++; next_face = 1 }
            }
            if (next_face) { next_face = 0; continue }
            a = FV[f,1]; b = FV[f,2]; c = FV[f,3]
            ux = X[b] - X[a]; uy = Y[b] - Y[a]; uz = Z[b] - Z[a]
            wx = X[c] - X[a]; wy = Y[c] - Y[a]; wz = Z[c] - Z[a]
            cx = uy * wz - uz * wy; cy = uz * wx - ux * wz; cz = ux * wy - uy * wx
            area2 = sqrt(sq(cx) + sq(cy) + sq(cz))
            if (a == b || b == c || a == c || area2 < 1e-12) degen++
            vol += (X[a] * (Y[b] * Z[c] - Z[b] * Y[c]) - Y[a] * (X[b] * Z[c] - Z[b] * X[c]) + \
                    Z[a] * (X[b] * Y[c] - Y[b] * X[c])) / 6
            for (k = 1; k <= 3; k++) {
                n = FN[f,k]
                if (NX[n] * cx + NY[n] * cy + NZ[n] * cz <= 0) disagree++
            }
            ta = FT[f,1]; tb = FT[f,2]; tc = FT[f,3]
            if ((U[tb] - U[ta]) * (W[tc] - W[ta]) - (U[tc] - U[ta]) * (W[tb] - W[ta]) <= 0) uvneg++
            for (k = 1; k <= 3; k++) {
                p0 = FV[f,k]; p1 = FV[f, k % 3 + 1]
                if (++dir[p0, p1] > 1) dupdir++
                key = p0 < p1 ? p0 SUBSEP p1 : p1 SUBSEP p0
                und[key]++
            }
        }
        ne = boundary = nonmanifold = 0
        for (key in und) { ne++; if (und[key] == 1) boundary++; if (und[key] > 2) nonmanifold++ }
        printf "nv %d\nnvt %d\nnvn %d\nntri %d\nnontri %d\nnoattr %d\nbadidx %d\n", \
               nv, nvt, nvn, nf, nontri, noattr, badidx
        printf "degen %d\ndupdir %d\nboundary %d\nnonmanifold %d\neuler %d\n", \
               degen, dupdir, boundary, nonmanifold, nv - ne + nf
        printf "vol %.6f\nmaxlen %.6g\ndisagree %d\nuvneg %d\n", vol, maxlen, disagree, uvneg
        printf "xmin %.6f\nxmax %.6f\nymin %.6f\nymax %.6f\nzmin %.6f\nzmax %.6f\n", \
               xmin, xmax, ymin, ymax, zmin, zmax
        printf "rmin %.6f\nrmax %.6f\n", rmin, rmax
        # normal at the highest and the lowest vertex (both are poles of the teapot)
        if (nvn == nv) printf "top_ny %.6f\nbottom_ny %.6f\n", NY[yhi], NY[ylo]
    }' "$1"
}

get() { sed -n "s/^$1 //p" <<<"$stats"; }
# true (1) when awk says so; used for float comparisons
is() { awk "BEGIN { exit !($1) }" && echo 1 || echo 0; }

check_mesh() { # name ntri nv nvt nvn closed(1/0) euler|- boundary
    local name=$1 ntri=$2 nv=$3 nvt=$4 nvn=$5 closed=$6 euler=$7 boundary=$8
    local obj=$dir/$name.obj
    if [ ! -s "$obj" ]; then bad "$name.obj exists" "missing or empty"; return 1; fi
    stats=$(obj_stats "$obj")
    check "$name: $ntri triangles, $nv v, $nvt vt, $nvn vn" \
        "got $(get ntri) tris, $(get nv) v, $(get nvt) vt, $(get nvn) vn" \
        "$(is "$(get ntri) == $ntri && $(get nv) == $nv && $(get nvt) == $nvt && $(get nvn) == $nvn")"
    check "$name: faces are triangles with v/vt/vn, indices in range" \
        "nontri=$(get nontri) noattr=$(get noattr) badidx=$(get badidx)" \
        "$(is "$(get nontri) + $(get noattr) + $(get badidx) == 0")"
    check "$name: no degenerate triangles" "$(get degen) degenerate" "$(is "$(get degen) == 0")"
    check "$name: consistent winding (each directed edge once, manifold)" \
        "$(get dupdir) repeated directed edges, $(get nonmanifold) edges with >2 faces" \
        "$(is "$(get dupdir) + $(get nonmanifold) == 0")"
    check "$name: $boundary open edges$([ "$closed" = 1 ] && echo " (watertight)")" \
        "$(get boundary) open edges" "$(is "$(get boundary) == $boundary")"
    if [ "$euler" != - ]; then
        check "$name: Euler characteristic V-E+F = $euler" "got $(get euler)" \
            "$(is "$(get euler) == $euler")"
    fi
    if [ "$closed" = 1 ] || [ "$name" = teapot ]; then   # the teapot's gaps are small
        check "$name: positive signed volume (outward winding)" "volume $(get vol)" \
            "$(is "$(get vol) > 0")"
    fi
    check "$name: unit normals agreeing with the winding" \
        "max | |n|-1 | = $(get maxlen), $(get disagree) corner normals facing away from their face" \
        "$(is "$(get maxlen) < 1e-5 && $(get disagree) == 0")"
    check "$name: texture unmirrored (every triangle counter-clockwise in uv)" \
        "$(get uvneg) triangles clockwise or flat in uv" "$(is "$(get uvneg) == 0")"
    local mtl=$dir/$name.mtl map
    if grep -q "^mtllib $name.mtl\$" "$obj" && [ -s "$mtl" ] && grep -q "^newmtl " "$mtl" &&
        grep -q "^usemtl $(sed -n 's/^newmtl //p' "$mtl")\$" "$obj"; then
        map=$(sed -n 's/^map_Kd //p' "$mtl")
        if [ -z "$map" ] || [ -s "$dir/$map" ]; then ok "$name: mtllib/usemtl/MTL${map:+ and $map} present"
        else bad "$name: map_Kd" "$map missing"; fi
    else
        bad "$name: mtllib/usemtl" "$name.mtl missing or not referenced"
    fi
    return 0
}

near() { is "($1) - ($2) < $3 && ($2) - ($1) < $3"; }

# ---- meshes ------------------------------------------------------------------------------------
# cube: 8 shared corners, 4 vt, 6 face normals
if check_mesh cube 12 8 4 6 1 2 0; then
    check "cube: edge 1 centred at the origin" "bounds $(get xmin)..$(get xmax)" \
        "$(is "$(get xmin) == -0.5 && $(get xmax) == 0.5 && $(get ymin) == -0.5 && $(get ymax) == 0.5 && $(get zmin) == -0.5 && $(get zmax) == 0.5")"
fi
# sphere 24 stacks x 48 slices: 2 poles + 23 rings; vt 23*49 + 2*48; 2*48 cap + 2*48*22 band
if check_mesh sphere 2208 1106 1223 1106 1 2 0; then
    check "sphere: radius 0.5" "radius $(get rmin)..$(get rmax)" \
        "$(is "$(get rmin) > 0.499997 && $(get rmax) < 0.500003")"   # 6 printed decimals
    check "sphere: poles have normals +Y/-Y" "$(get top_ny) $(get bottom_ny)" \
        "$(is "$(get top_ny) == 1 && $(get bottom_ny) == -1")"
fi
# torus 48 x 24: 1152 v, 49*25 vt, 2304 triangles, genus 1
if check_mesh torus 2304 1152 1225 1152 1 0 0; then
    check "torus: axis Y, tube 0.15 around radius 0.35" "y $(get ymin)..$(get ymax) r..$(get rmax)" \
        "$(is "$(get ymin) == -0.15 && $(get ymax) == 0.15 && $(get rmax) < 0.500001")"
fi
if check_mesh floor 2 4 4 1 0 - 4; then
    check "floor: normal +Y" "vn is $(grep '^vn ' "$dir/floor.obj")" \
        "$(grep -qx 'vn 0.000000 1.000000 0.000000' "$dir/floor.obj" && echo 1 || echo 0)"
    check "floor: 20 x 20 at y = 0" "$(get xmin)..$(get xmax) y $(get ymin)..$(get ymax)" \
        "$(is "$(get xmin) == -10 && $(get xmax) == 10 && $(get zmin) == -10 && $(get zmax) == 10 && $(get ymin) == 0 && $(get ymax) == 0")"
fi
# teapot: N x N quads per patch over 32 patches; the 8 patches at the knob top and the bottom
# centre lose one triangle per quad of their collapsed row; the open edges are the lid rim and
# the body rim (4 patches x N each), and both ends of the spout and of the handle (2 x N each).
steps=$(sed -n 's/.*patch resolution \([0-9]*\) x .*/\1/p' "$dir/teapot.obj" 2>/dev/null)
if [ -z "$steps" ]; then
    bad "teapot: header names its patch resolution" "no '# ... patch resolution N x N' line"
else
    nv=$(awk '/^v /{n++} END{print n+0}' "$dir/teapot.obj")
    if check_mesh teapot $((64 * steps * steps - 8 * steps)) "$nv" $((32 * (steps + 1) ** 2)) \
        "$nv" 0 - $((16 * steps)); then
        check "teapot: 2 units wide (x), centred in x and z, bottom at y = 0" \
            "x $(get xmin)..$(get xmax) y $(get ymin)..$(get ymax) z $(get zmin)..$(get zmax)" \
            "$(is "$(near "$(get xmax) - $(get xmin)" 2 2e-6) && $(near "$(get xmax) + $(get xmin)" 0 2e-6) && $(near "$(get zmax) + $(get zmin)" 0 2e-6) && $(get ymin) == 0 && $(get ymax) > 0.9 && $(get ymax) < 1.0")"
        check "teapot: degenerate poles have axial normals (knob up, bottom down)" \
            "top ny $(get top_ny), bottom ny $(get bottom_ny)" \
            "$(is "$(get top_ny) > 0.9999 && $(get bottom_ny) < -0.9999")"
    fi
fi

# ---- images ------------------------------------------------------------------------------------
png_size() { # prints "W H depth colortype" from the IHDR chunk, or nothing
    local f=$1
    [ "$(od -An -tx1 -N8 "$f" 2>/dev/null | tr -d ' \n')" = 89504e470d0a1a0a ] || return
    od -An -tu1 -j16 -N10 "$f" | awk '{ print $1*16777216+$2*65536+$3*256+$4, \
        $5*16777216+$6*65536+$7*256+$8, $9, $10 }'
}
for img in checker brick uvgrid stripes sky_posx sky_negx sky_posy sky_negy sky_posz sky_negz; do
    f=$dir/$img.png
    read -r w h depth ctype <<<"$(png_size "$f")"
    case $img in sky_*) want="w == 256 && h == 256" ;;
                 *) want="w == h && (w == 256 || w == 512)" ;; esac
    if [ -z "${w:-}" ]; then bad "$img.png is a PNG" "missing or not a PNG"; continue; fi
    check "$img.png: ${w}x$h 8-bit RGB" "want $want, depth 8, colour type 2 (got $depth/$ctype)" \
        "$(awk -v w="$w" -v h="$h" "BEGIN { exit !($want) }" && [ "$depth" = 8 ] && [ "$ctype" = 2 ] && echo 1 || echo 0)"
done

# ---- cubemap content (python3 stdlib: zlib) ------------------------------------------------------
pyout=$(mktemp)
if command -v python3 >/dev/null 2>&1; then
    python3 - "$dir" <<'PY'
import sys, zlib, struct
d = sys.argv[1]
def load(path):  # 8-bit RGB PNG -> (w, h, rows of bytes)
    data = open(path, 'rb').read()
    pos, idat = 8, b''
    while pos < len(data):
        n, typ = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if typ == b'IHDR': w, h = struct.unpack('>II', body[:8])
        if typ == b'IDAT': idat += body
        pos += 12 + n
    raw, bpp, stride = zlib.decompress(idat), 3, w * 3
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride]); i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]; c = prev[x - bpp] if x >= bpp else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line)); prev = line
    return w, h, rows
names = ['posx', 'negx', 'posy', 'negy', 'posz', 'negz']
try:
    faces = [load('%s/sky_%s.png' % (d, n)) for n in names]
except Exception as e:
    print('FAIL sky: cannot decode faces: %s' % e); print('RESULT 0 1'); sys.exit(0)
S = faces[0][0]
def px(f, i, j): r = faces[f][2][j]; return r[3 * i:3 * i + 3]
# GL cube-map convention, (sc, tc) -> direction, row 0 = t = 0 (as in assets/gen/sky.c)
def face_dir(f, sc, tc):
    return [(1, -tc, -sc), (-1, -tc, sc), (sc, 1, tc), (sc, -1, -tc), (sc, -tc, 1), (-sc, -tc, -1)][f]
def lookup(x, y, z):  # direction -> (face, i, j), GL face selection
    ax, ay, az = abs(x), abs(y), abs(z)
    if ax >= ay and ax >= az: f, sc, tc, ma = (0, -z, -y, ax) if x > 0 else (1, z, -y, ax)
    elif ay >= az: f, sc, tc, ma = (2, x, z, ay) if y > 0 else (3, x, -z, ay)
    else: f, sc, tc, ma = (4, x, -y, az) if z > 0 else (5, -x, -y, az)
    s, t = (sc / ma + 1) / 2, (tc / ma + 1) / 2
    return f, min(S - 1, int(s * S)), min(S - 1, int(t * S))
passed = failed = 0
def check(name, cond, why):
    global passed, failed
    if cond: passed += 1; print('ok   ' + name)
    else: failed += 1; print('FAIL %s: %s' % (name, why))
# 1. seams: the texel just outside each border texel is found on the neighbouring face
#    and must have nearly the same colour (they are one texel apart in direction).
worst, total, count, faces_seen = 0, 0, 0, set()
for f in range(6):
    for k in range(S):
        for (i, j, di, dj) in ((k, 0, 0, -1), (k, S - 1, 0, 1), (0, k, -1, 0), (S - 1, k, 1, 0)):
            sc = 2 * (i + di + 0.5) / S - 1; tc = 2 * (j + dj + 0.5) / S - 1
            g, gi, gj = lookup(*face_dir(f, sc, tc))
            faces_seen.add((f, g))
            diff = max(abs(a - b) for a, b in zip(px(f, i, j), px(g, gi, gj)))
            worst = max(worst, diff); total += diff; count += 1
check('sky: every face borders 4 others', all(len({g for (f, g) in faces_seen if f == x} - {x}) == 4 for x in range(6)), 'bad adjacency')
check('sky: faces agree across all 12 edges (mean %.2f, max %d)' % (total / count, worst),
      total / count < 2.0 and worst <= 24, 'mean %.2f max %d per channel' % (total / count, worst))
# 2. orientation: side faces have sky (blue > red) in the top row, ground (red > blue) at the bottom
side_ok = all(px(f, S // 2, 0)[2] > px(f, S // 2, 0)[0] and px(f, S // 2, S - 1)[0] > px(f, S // 2, S - 1)[2]
              for f in (0, 1, 4, 5))
check('sky: side faces have sky on top, ground below', side_ok, 'a side face is upside down')
check('sky: posy is sky, negy is ground', px(2, S // 2, S // 2)[2] > px(2, S // 2, S // 2)[0] and
      px(3, S // 2, S // 2)[0] > px(3, S // 2, S // 2)[2], 'posy/negy swapped')
# 3. the sun: brightest texel of all faces lies next to the corner shared by posx, posy, posz
best = max(((sum(px(f, i, j)), f, i, j) for f in range(6) for j in range(S) for i in range(S)))
_, f, i, j = best
x, y, z = face_dir(f, 2 * (i + 0.5) / S - 1, 2 * (j + 0.5) / S - 1)
n = (x * x + y * y + z * z) ** 0.5
cosang = (x + y + z) / n / 3 ** 0.5
check('sun toward normalize(1,1,1) (brightest texel on face %s)' % names[f], cosang > 0.999, 'cos %.4f' % cosang)
print('RESULT %d %d' % (passed, failed))
PY
else
    echo "RESULT skip"
fi > "$pyout" 2>&1
while read -r line; do
    case $line in
        "RESULT skip") skp "sky content checks" "python3 not found" ;;
        RESULT*) read -r _ p f <<<"$line"; pass=$((pass + p)); fail=$((fail + f)) ;;
        *) echo "$line" ;;
    esac
done < "$pyout"
grep -q '^RESULT' "$pyout" || bad "sky content checks" "python3 crashed"
rm -f "$pyout"

# ---- determinism -------------------------------------------------------------------------------
if [ -x "$gen" ]; then
    tmp=$(mktemp -d)
    mkdir "$tmp/a" "$tmp/b"
    if "$gen" "$tmp/a" && "$gen" "$tmp/b"; then
        if diff -r "$tmp/a" "$tmp/b" >/dev/null; then ok "two generator runs are byte-identical"
        else bad "two generator runs are byte-identical" "$(diff -rq "$tmp/a" "$tmp/b" | head -3)"; fi
        if [ -z "$(for f in "$tmp"/a/*; do cmp -s "$f" "$dir/$(basename "$f")" || echo x; done)" ]; then
            ok "$dir matches a fresh run"
        else
            bad "$dir matches a fresh run" "stale files: rerun $gen $dir"
        fi
        n=$(find "$tmp/a" -type f | wc -l)
        check "generator writes 20 files" "wrote $n" "$(is "$n == 20")"
    else
        bad "generator runs" "$gen failed"
    fi
    if "$gen" "$tmp/does/not/exist" 2>/dev/null; then bad "generator fails on a bad directory" "exit 0"
    else ok "generator fails on a bad directory"; fi
    rm -rf "$tmp"
else
    skp "determinism" "$gen not built"
fi

echo "$pass passed, $fail failed, $skip skipped"
[ "$fail" -eq 0 ]
