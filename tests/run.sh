#!/usr/bin/env bash
# tests/run.sh: run every test suite and end with ONE summary line "N passed, N failed, N skipped".
# Each suite prints its own "N passed, N failed, N skipped" as its last line; this adds them up.
#   tests/run.sh          unit tests, oracle (Mesa) tests, end-to-end tests  (build/)
#   tests/run.sh --asan   unit + end-to-end tests of the sanitizer build     (build/asan/)
#   tests/run.sh --all    both of the above (what `make test` runs)
# RASTTY_TEST_ONLY=TEXT runs only the suites whose name contains TEXT (e2e, asan/e2e/viewer).
# Suites run side by side, RASTTY_TEST_JOBS at once (default: three per core; 1 runs them one
# after another): most of an end-to-end suite's time is waiting for a terminal, and every
# suite has its own tmux server and output folder (build/e2e/NAME, NAME-asan). Those that
# took longest last time (build/test-times; on a clean tree, a list below) start first.
# Each suite's output is kept until it ends and printed whole, in the order above, under
# "=== NAME (WALL s, cpu CPU s)" (CPU: user + system time of its processes); the line
# before the summary gives the whole run's wall time.
set -u
cd "$(dirname "$0")/.."
mode=${1:-}
jobs=${RASTTY_TEST_JOBS:-$(( $(nproc 2>/dev/null || echo 1) * 3 ))}
[ "$jobs" -ge 1 ] 2>/dev/null || jobs=1
times_file=build/test-times
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rastty-tests.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
secs() { printf '%d.%d' $(( $1 / 1000 )) $(( $1 % 1000 / 100 )); } # ms as "12.3"

# ---- the suites, in the order they are reported ----
names=() tags=() cmds=()
add() { # tag name command...
    [[ -z ${RASTTY_TEST_ONLY:-} || $2 == *"$RASTTY_TEST_ONLY"* ]] || return 0
    tags+=("$1"); names+=("$2"); shift 2
    cmds+=("$(printf '%q ' "$@")")
}
suites() { # tag: plain | asan
    local tag=$1 t unit=build/unit-tests
    [ "$tag" = asan ] && unit=build/asan/unit-tests
    add "$tag" "$tag/unit" "$unit"
    [ "$tag" = plain ] && add "$tag" "$tag/layers" python3 tests/layers.py
    for t in tests/e2e/*.sh; do
        [ -e "$t" ] || continue
        add "$tag" "$tag/e2e/$(basename "$t" .sh)" bash "$t"
    done
    if [ "$tag" = plain ]; then
        add "$tag" "$tag/assets" bash tests/assets_check.sh assets build/generate-assets
    fi
    if [ "$tag" = plain ] && [ -x tests/oracle/run.sh ]; then
        add "$tag" "$tag/oracle" tests/oracle/run.sh
    fi
}
case "$mode" in
    --asan) suites asan ;;
    --all) suites plain; suites asan ;;
    *) suites plain ;;
esac
n=${#names[@]}

# the environment a suite runs in
suite_env() { # tag
    # no level-of-detail cache (lod_cache.h) unless a test asks for one: every suite builds
    # its levels, and nothing is written under ~/.cache
    export RASTTY_CACHE_DIR=
    if [ "$1" = asan ]; then
        export RASTTY_BIN=build/asan/rastty UNIT_BIN=build/asan/unit-tests RASTTY_ASAN=1
        export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
        export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    else
        export RASTTY_BIN=./rastty UNIT_BIN=build/unit-tests RASTTY_ASAN=
    fi
}
# run suite $1 in the background: its output, exit status and wall time (ms) into $tmp
start_suite() {
    local i=$1
    (
        suite_env "${tags[i]}"
        t0=$(now_ms)
        eval "${cmds[i]}" > "$tmp/$i.out" 2>&1 < /dev/null
        rc=$?
        echo $(( $(now_ms) - t0 )) > "$tmp/$i.ms"
        times > "$tmp/$i.cpu" # line 2: the suite's processes' user and system time
        echo "$rc" > "$tmp/$i.rc.new" && mv "$tmp/$i.rc.new" "$tmp/$i.rc" # last: the suite is over
    ) &
}

# start order: longest last time first, the others in the order above; a clean tree (CI) has
# no record: these took longest on a 2-core machine (ms)
declare -A last=([plain/oracle]=80000 [asan/e2e/viewer]=45000 [plain/e2e/viewer]=28000
                 [asan/unit]=25000 [asan/e2e/slow_link]=17000 [plain/e2e/slow_link]=17000)
if [ -r "$times_file" ]; then
    while read -r ms name; do last[$name]=$ms; done < "$times_file"
fi
order=$(for ((i = 0; i < n; i++)); do echo "${last[${names[i]}]:-0} $i"; done |
        sort -k1,1nr -k2,2n | cut -d' ' -f2)

# ---- run ----
total_p=0 total_f=0 total_s=0
failed_suites=()
report() { # i: print suite i whole and add up its summary line
    local i=$1 name=${names[$1]} rc ms line cpu
    rc=$(cat "$tmp/$i.rc"); ms=$(cat "$tmp/$i.ms")
    cpu=$(awk '{ gsub(/s/, "", $1); gsub(/s/, "", $2); split($1, u, "m"); split($2, y, "m")
                 printf "%.1f", u[1] * 60 + u[2] + y[1] * 60 + y[2] }' <(tail -n 1 "$tmp/$i.cpu"))
    echo "=== $name ($(secs "$ms") s, cpu $cpu s)"
    cat "$tmp/$i.out"
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed(, [0-9]+ skipped)?$' "$tmp/$i.out" | tail -n 1)
    if [ -z "$line" ]; then
        echo "!!! $name: no summary line (exit $rc)"
        total_f=$((total_f + 1)); failed_suites+=("$name"); return
    fi
    local p f s
    p=$(echo "$line" | sed -E 's/^([0-9]+) passed.*/\1/')
    f=$(echo "$line" | sed -E 's/.* ([0-9]+) failed.*/\1/')
    s=$(echo "$line" | sed -nE 's/.* ([0-9]+) skipped$/\1/p'); s=${s:-0}
    total_p=$((total_p + p)); total_s=$((total_s + s)); total_f=$((total_f + f))
    if [ "$f" -ne 0 ] || [ "$rc" -ne 0 ]; then
        [ "$f" -eq 0 ] && total_f=$((total_f + 1))
        failed_suites+=("$name")
    fi
}
t_start=$(now_ms)
started=0 next=0
finished() { local f=("$tmp"/*.rc); [ -e "${f[0]}" ] && echo ${#f[@]} || echo 0; }
flush() { while [ "$next" -lt "$n" ] && [ -e "$tmp/$next.rc" ]; do report "$next"; next=$((next + 1)); done; }
for i in $order; do
    while [ $((started - $(finished))) -ge "$jobs" ]; do
        wait -n 2>/dev/null || sleep 0.1
        flush
    done
    start_suite "$i"; started=$((started + 1))
done
while [ "$(finished)" -lt "$n" ]; do
    wait -n 2>/dev/null || sleep 0.1
    flush
done
wait
flush

# this run's times for the next run's start order (kept for suites this run did not have)
mkdir -p "$(dirname "$times_file")"
for ((i = 0; i < n; i++)); do last[${names[i]}]=$(cat "$tmp/$i.ms"); done
for name in "${!last[@]}"; do echo "${last[$name]} $name"; done | sort -k1,1nr > "$times_file.new" &&
    mv -f "$times_file.new" "$times_file"

[ ${#failed_suites[@]} -gt 0 ] && echo "failed suites: ${failed_suites[*]}"
echo "$n suites in $(secs $(( $(now_ms) - t_start ))) s, up to $jobs at once"
echo "${total_p} passed, ${total_f} failed, ${total_s} skipped"
[ "$total_f" -eq 0 ]
