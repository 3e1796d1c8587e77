#!/usr/bin/env bash
# tests/bench_scale.sh: does a frame cost what the screen shows or what the file holds? The
# same displaced sphere (build/bench/gensphere: 10k, 100k, 1M and 4M triangles, framed: the
# same size on screen), a generated block world (build/bench/genvoxels) and the dense shared
# models (lost_empire, sports car, bunny) at
# 160x96 and 640x480, one thread and two. `make bench` prints it (issue 24's table).
#
#   tests/bench_scale.sh [--repeat N] [--sizes "10000 ..."] [--screens "160x96 ..."]
#                        [--threads "1 ..."] [--csv FILE]
#
# (--sizes: the spheres' triangle counts, default 10k 100k 1M 4M; --screens default 160x96
# 640x480; --threads default 1 2.)
#
# Per model, size and thread count: `render --eye 0.5,0.364,0.8 --frame --repeat N --stats`
# (median_ms) with --lod off (every triangle of the file: what must not change a pixel),
# with --lod auto (the levels of detail: its PSNR against --lod off, by
# build/oracle/compare), with --lod clusters (the cluster hierarchy, scene/dag.h: dag_ms,
# its PSNR, the triangles of its cut), and — where this build has the switch — --lod off
# --cluster-cull off (noclu_ms: no clusters, on by default; speedup = noclu_ms / off_ms; the
# clusters the --lod off run culled of those it tested; the pictures must be the same
# bytes: "same" or "DIFFER"), and --lod off
# --hidden-cull off (nohide_ms: every triangle set up, none dropped as hidden behind the
# depth so far; hidden: the triangles the --lod off run dropped so; hbytes: the pictures
# compared the same way). load_ms is
# render's, rss_MB the peak resident memory of the --lod off run (/usr/bin/time), tris the
# triangles drawn. Mesa llvmpipe on the same mesh and camera (build/bench/glbench, OSMesa,
# as tests/bench_speed.sh runs it: the camera rastty's --frame chose, from the --lod off
# run's "camera:" line; per-pixel Phong, no culling, as rastty's defaults draw these
# files; the spheres' PLY drawn indexed, OBJ as triangles; LP_NUM_THREADS=0 for one
# thread, =2 for two; median of N frames after 2 of warm-up): gl_ms, and the ratios
# rastty/llvmpipe of off, auto and clusters (issue 24's target: <= 0.2x at 160x96, one
# thread). Without OSMesa (no glbench) those columns are "-". The
# sphere's files are made once in build/bench/scale (never in the repository). Then the
# memory each model's chain and hierarchy hold against its own geometry (render --stats's
# "levels:" and "hierarchy:" lines, from the first screen's runs), and the level cache's
# load times, and what the occluders (--occluders) save. Numbers, never verdicts.
set -u
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
S=${RASTTY_SHARED:-../shared}/models
GEN=build/bench/gensphere
CMP=build/oracle/compare
GL=build/bench/glbench
D=build/bench/scale
repeat=9 sizes="10000 100000 1000000 4000000" screens="160x96 640x480" threads="1 2" csv=
while [ $# -gt 0 ]; do
    case $1 in
    --repeat) repeat=$2; shift ;;
    --sizes) sizes=$2; shift ;;
    --screens) screens=$2; shift ;;
    --threads) threads=$2; shift ;;
    --csv) csv=$2; shift ;;
    *) echo "usage: tests/bench_scale.sh [--repeat N] [--sizes \"N ...\"] [--screens \"WxH ...\"] [--threads \"N ...\"] [--csv FILE]" >&2
       exit 2 ;;
    esac
    shift
done
if [ ! -x "$GEN" ]; then
    echo "-- scale: skipped ($GEN missing: make build/bench/gensphere)"
    exit 0
fi
mkdir -p "$D"
models=()
for n in $sizes; do
    f=$D/sphere_$n.ply
    [ -f "$f" ] || "$GEN" "$n" "$f" >/dev/null || { echo "-- scale: $GEN $n failed"; exit 1; }
    models+=("$f")
done
# the block world (build/bench/genvoxels 160: 121k triangles, every vertex a uv seam)
VOX=build/bench/genvoxels
if [ -x "$VOX" ]; then
    b=$D/blocks_160
    { [ -f "$b/blocks.obj" ] || { mkdir -p "$b" && "$VOX" 160 "$b" >/dev/null; }; } &&
        models+=("$b/blocks.obj")
else
    echo "   (no block world: make build/bench/genvoxels)"
fi
for m in lost_empire/lost_empire.obj sports_car/sportsCar.obj bunny/bunny.obj; do
    if [ -f "$S/$m" ]; then models+=("$S/$m"); else echo "   (no $S/$m: skipped)"; fi
done
cull=0 hide=0
"$BIN" --help 2>&1 | grep -q -- --cluster-cull && cull=1
"$BIN" --help 2>&1 | grep -q -- --hidden-cull && hide=1
if [ ! -x "$GL" ]; then
    echo "   (no llvmpipe columns: $GL missing; it needs OSMesa: apt-get install libosmesa6-dev, make oracle-build)"
    GL=
fi
ratio() { [ -n "$2" ] && [ "$2" != - ] && [ -n "$1" ] && [ "$1" != - ] &&
          awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3fx", a / b }' || echo -; }
TIME=
[ -x /usr/bin/time ] && TIME="/usr/bin/time -f rss_kb=%M"
ms_of() { sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p' | tail -n 1; }
echo "-- scale: median ms of $repeat frames, eye 0.5,0.364,0.8 framed; auto's PSNR against --lod off;"
echo "   gl_ms: Mesa llvmpipe on the same mesh and camera, x/gl: rastty's ms over llvmpipe's"
printf '  %-20s %-8s %2s %9s %9s %9s %8s %9s %6s %9s %6s %8s %9s %7s %15s %5s %9s %7s %6s %9s %8s %8s %8s\n' model size th load_ms rss_MB \
    off_ms tris auto_ms PSNR dag_ms PSNR dag_tris noclu_ms speedup culled/tested bytes \
    nohide_ms hidden hbytes gl_ms off/gl auto/gl dag/gl
[ -n "$csv" ] && echo "model,size,threads,load_ms,rss_mb,off_ms,tris,auto_ms,auto_psnr,dag_ms,dag_psnr,dag_tris,noclu_ms,speedup,culled_tested,same_bytes,nohide_ms,hidden,nohide_same_bytes,gl_ms,off_gl,auto_gl,dag_gl" > "$csv"
declare -A mem_chain mem_dag
for m in "${models[@]}"; do
    name=$(basename "$m"); name=${name%.*}
    for size in $screens; do
        for th in $threads; do
            cam=(--eye 0.5,0.364,0.8 --frame --size "$size" --threads "$th" --repeat "$repeat" --stats)
            o=$D/$name.$size.$th
            st=$($TIME "$BIN" render "$m" "${cam[@]}" --lod off --out "$o.off.ppm" \
                --depth-out "$o.off.pfm" 2>&1) || { echo "  $name: render failed"; continue 3; }
            off=$(ms_of <<<"$st")
            cl=$(sed -n 's/^clusters: tested \([0-9]*\), culled \([0-9]*\).*/\2\/\1/p' <<<"$st")
            cl=${cl:--}
            load=$(sed -n 's/.*load_ms=\([0-9.]*\).*/\1/p' <<<"$st" | tail -n 1)
            tris=$(sed -n 's/^tris in .* drawn \([0-9]*\).*/\1/p' <<<"$st" | tail -n 1)
            hid=$(sed -n 's/^tris in .* hidden \([0-9]*\),.*/\1/p' <<<"$st" | tail -n 1)
            hid=${hid:--}
            rss=$(sed -n 's/^rss_kb=\([0-9]*\)/\1/p' <<<"$st")
            rss=$([ -n "$rss" ] && awk -v k="$rss" 'BEGIN { printf "%.0f", k / 1024 }' || echo -)
            camv=()
            read -r -a camv <<<"$(sed -n 's/^camera: //p' <<<"$st" | tail -n 1)"
            gl=-
            if [ -n "$GL" ] && [ ${#camv[@]} -gt 0 ]; then
                lp=0
                [ "$th" -gt 1 ] && lp=$th
                gl=$(LP_NUM_THREADS=$lp "$GL" "$m" "${camv[@]}" --size "$size" --shade phong \
                    --cull none --frames "$repeat" --warmup 2 2>/dev/null | ms_of)
                gl=${gl:--}
            fi
            st=$("$BIN" render "$m" "${cam[@]}" --lod auto --out "$o.auto.ppm" \
                --depth-out "$o.auto.pfm" 2>&1)
            auto=$(ms_of <<<"$st")
            mem_chain[$name]=$(sed -n 's/^levels: .*, \([0-9.]*\) MB, \([0-9.]*x\) .*/\1 MB \2/p' <<<"$st")
            psnr=-
            [ -x "$CMP" ] && psnr=$("$CMP" "$o.auto.ppm" "$o.auto.pfm" "$o.off.ppm" "$o.off.pfm" |
                sed -n 's/.*psnr=\([0-9.inf]*\).*/\1/p')
            dag=- dpsnr=- dtris=-
            if "$BIN" --help 2>&1 | grep -q 'clusters:PX'; then
                st=$("$BIN" render "$m" "${cam[@]}" --lod clusters --out "$o.dag.ppm" \
                    --depth-out "$o.dag.pfm" 2>&1)
                dag=$(ms_of <<<"$st")
                mem_dag[$name]=$(sed -n 's/^hierarchy: .*, \([0-9.]*\) MB, \([0-9.]*x\) their own geometry.s \([0-9.]*\) MB.*/\1 MB \2 \3/p' <<<"$st")
                dtris=$(sed -n 's/^lod: cluster hierarchy, .*, \([0-9]*\) triangles$/\1/p' <<<"$st")
                dtris=${dtris:--}
                [ -x "$CMP" ] && dpsnr=$("$CMP" "$o.dag.ppm" "$o.dag.pfm" "$o.off.ppm" "$o.off.pfm" |
                    sed -n 's/.*psnr=\([0-9.inf]*\).*/\1/p')
            fi
            nc=- sp=- eq=-
            if [ $cull = 1 ]; then
                st=$("$BIN" render "$m" "${cam[@]}" --lod off --cluster-cull off \
                    --out "$o.nc.ppm" --depth-out "$o.nc.pfm" 2>&1)
                nc=$(ms_of <<<"$st")
                sp=$(awk -v a="$nc" -v b="$off" 'BEGIN { printf "%.2fx", a / b }')
                eq=same
                cmp -s "$o.nc.ppm" "$o.off.ppm" && cmp -s "$o.nc.pfm" "$o.off.pfm" || eq=DIFFER
            fi
            nh=- heq=-
            if [ $hide = 1 ]; then
                st=$("$BIN" render "$m" "${cam[@]}" --lod off --hidden-cull off \
                    --out "$o.nh.ppm" --depth-out "$o.nh.pfm" 2>&1)
                nh=$(ms_of <<<"$st")
                heq=same
                cmp -s "$o.nh.ppm" "$o.off.ppm" && cmp -s "$o.nh.pfm" "$o.off.pfm" || heq=DIFFER
            fi
            ro=$(ratio "$off" "$gl") ra=$(ratio "$auto" "$gl") rd=$(ratio "$dag" "$gl")
            printf '  %-20s %-8s %2s %9s %9s %9s %8s %9s %6s %9s %6s %8s %9s %7s %15s %5s %9s %7s %6s %9s %8s %8s %8s\n' "$name" "$size" \
                "$th" "$load" "$rss" "$off" "$tris" "$auto" "$psnr" "$dag" "$dpsnr" "$dtris" "$nc" "$sp" "$cl" "$eq" \
                "$nh" "$hid" "$heq" "$gl" "$ro" "$ra" "$rd"
            [ -n "$csv" ] && echo "$name,$size,$th,$load,$rss,$off,$tris,$auto,$psnr,$dag,$dpsnr,$dtris,$nc,$sp,$cl,$eq,$nh,$hid,$heq,$gl,$ro,$ra,$rd" >> "$csv"
        done
    done
done
# memory (issue 24: clusters and levels at most 1.5x the mesh's own): render --stats's
# "levels:" (the chain, --lod auto) and "hierarchy:" (--lod clusters, after dag_settle)
echo "-- memory: the chain's and the hierarchy's bytes, and their ratio to the mesh's own geometry"
printf '  %-20s %9s %8s %9s %8s %9s\n' model chain_MB chain_x dag_MB dag_x own_MB
for m in "${models[@]}"; do
    name=$(basename "$m"); name=${name%.*}
    read -r cb _ cx <<<"${mem_chain[$name]:-- - -}"
    read -r db _ dx own <<<"${mem_dag[$name]:-- - - -}"
    printf '  %-20s %9s %8s %9s %8s %9s\n' "$name" "$cb" "$cx" "$db" "$dx" "${own:--}"
done
# occluders (--occluders, on by default; render/frontend.h, "Occluders"): each item's
# triangles of the last frame hide what lies strictly behind them, from render --repeat's
# second frame on: --lod auto with them off and on, one thread, the fastest frame of each
# run, the pictures compared
if "$BIN" --help 2>&1 | grep -q -- --occluders; then
    echo "-- occluders: --lod auto, one thread, min_ms (the fastest frame: the first has none, the second's list is every triangle drawn) with --occluders off / on; the triangles they hid"
    min_of() { sed -n 's/.*min_ms=\([0-9.]*\).*/\1/p' | tail -n 1; }
    printf '  %-20s %-8s %9s %9s %8s %6s %9s\n' model size noocc_ms occ_ms speedup bytes occluded
    for m in "${models[@]}"; do
        name=$(basename "$m"); name=${name%.*}
        for size in $screens; do
            o=$D/$name.$size.occ
            cam=(--eye 0.5,0.364,0.8 --frame --size "$size" --threads 1 --repeat "$repeat" --stats --lod auto)
            a=$("$BIN" render "$m" "${cam[@]}" --occluders off --out "$o.0.ppm" --depth-out "$o.0.pfm" 2>&1 | min_of)
            st=$("$BIN" render "$m" "${cam[@]}" --out "$o.1.ppm" --depth-out "$o.1.pfm" 2>&1)
            b=$(min_of <<<"$st")
            hid=$(sed -n 's/^occluders: .* \([0-9]*\) triangles (of those hidden)$/\1/p' <<<"$st")
            eq=same
            cmp -s "$o.0.ppm" "$o.1.ppm" && cmp -s "$o.0.pfm" "$o.1.pfm" || eq=DIFFER
            sp=$(awk -v a="$a" -v b="$b" 'BEGIN { if (b > 0) printf "%.2fx", a / b; else print "-" }')
            printf '  %-20s %-8s %9s %9s %8s %6s %9s\n' "$name" "$size" "$a" "$b" "$sp" "$eq" "${hid:-0}"
        done
    done
fi
# the cache of chains (lod_cache.h): render's load_ms with --lod off, with --lod auto
# building the chain (an empty cache folder), and with --lod auto reading the file the run
# before wrote
echo "-- the level cache: load_ms of --lod off / auto, building / auto, from the cache"
ld_of() { sed -n 's/.*load_ms=\([0-9.]*\).*/\1/p' | tail -n 1; }
for m in "${models[@]}"; do
    name=$(basename "$m"); name=${name%.*}
    c=$D/cache.$$
    rm -rf "$c"
    off=$(RASTTY_CACHE_DIR= "$BIN" render "$m" --lod off --stats --out $D/c.ppm 2>&1 | ld_of)
    build=$(RASTTY_CACHE_DIR=$c "$BIN" render "$m" --lod auto --stats --out $D/c.ppm 2>&1 | ld_of)
    st=$(RASTTY_CACHE_DIR=$c "$BIN" render "$m" --lod auto --stats --out $D/c.ppm 2>&1)
    read=$(ld_of <<<"$st")
    grep -q 'chains read' <<<"$st" || read="$read (no file: no chain, or under 131072 triangles)"
    printf '  %-20s %9s %9s %9s\n' "$name" "$off" "$build" "$read"
    rm -rf "$c"
done
