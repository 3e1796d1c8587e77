#!/usr/bin/env bash
# tests/run.sh: run every test suite and end with ONE summary line "N passed, N failed, N skipped".
# Each suite prints its own "N passed, N failed, N skipped" as its last line; this adds them up.
# Each suite's output starts with "=== NAME (WALL s)": how long it took.
#   tests/run.sh          unit tests, oracle (Mesa) tests, end-to-end tests  (build/)
#   tests/run.sh --asan   unit + end-to-end tests of the sanitizer build     (build/asan/)
#   tests/run.sh --all    both of the above (what `make test` runs)
set -u
cd "$(dirname "$0")/.."
mode=${1:-}
total_p=0 total_f=0 total_s=0
failed_suites=()

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
secs() { printf '%d.%d' $(( $1 / 1000 )) $(( $1 % 1000 / 100 )); } # ms as "12.3"

run_suite() { # name command...
    local name=$1; shift
    local out rc t0
    t0=$(now_ms)
    out=$("$@" 2>&1); rc=$?
    echo "=== $name ($(secs $(( $(now_ms) - t0 ))) s)"
    printf '%s\n' "$out"
    local line
    line=$(printf '%s\n' "$out" | grep -E '^[0-9]+ passed, [0-9]+ failed(, [0-9]+ skipped)?$' | tail -n 1)
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

suites() { # tag: plain | asan
    local tag=$1
    if [ "$tag" = asan ]; then
        export RASTTY_BIN=build/asan/rastty UNIT_BIN=build/asan/unit-tests RASTTY_ASAN=1
        export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
        export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    else
        export RASTTY_BIN=./rastty UNIT_BIN=build/unit-tests RASTTY_ASAN=
    fi
    run_suite "$tag/unit" "$UNIT_BIN"
    [ "$tag" = plain ] && run_suite "$tag/layers" python3 tests/layers.py
    for t in tests/e2e/*.sh; do
        [ -e "$t" ] || continue
        run_suite "$tag/e2e/$(basename "$t" .sh)" bash "$t"
    done
    if [ "$tag" = plain ]; then
        run_suite "$tag/assets" bash tests/assets_check.sh assets build/generate-assets
    fi
    if [ "$tag" = plain ] && [ -x tests/oracle/run.sh ]; then
        run_suite "$tag/oracle" tests/oracle/run.sh
    fi
}
case "$mode" in
    --asan) suites asan ;;
    --all) suites plain; suites asan ;;
    *) suites plain ;;
esac
[ ${#failed_suites[@]} -gt 0 ] && echo "failed suites: ${failed_suites[*]}"
echo "${total_p} passed, ${total_f} failed, ${total_s} skipped"
[ "$total_f" -eq 0 ]
