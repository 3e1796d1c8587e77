#!/usr/bin/env bash
# tests/soak_e2e.sh [RUNS]: the end-to-end suites RUNS times in a row (default 20) with both
# cores kept busy beside them (`stress -c $(nproc)`, when stress is installed), as the tests
# must pass on a loaded machine; prints each run's summary line and the count that passed.
# Build first (make, make build/unit-tests). Not part of make test: it takes ~1 h on 2 cores.
set -u
cd "$(dirname "$0")/.."
runs=${1:-20}
sp=
if command -v stress >/dev/null; then
    stress -c "$(nproc)" >/dev/null 2>&1 &
    sp=$!
else
    echo "(stress not installed: the runs go without load beside them)"
fi
# (its workers first: once the parent is gone they are no longer its children)
trap '[ -n "$sp" ] && { pkill -P "$sp"; kill "$sp"; } 2>/dev/null' EXIT
pass=0
for i in $(seq "$runs"); do
    t0=$(date +%s)
    out=$(RASTTY_TEST_ONLY=plain/e2e tests/run.sh 2>&1)
    rc=$?
    echo "run $i: rc=$rc, $(( $(date +%s) - t0 )) s, $(tail -n 1 <<<"$out"), load $(cut -d' ' -f1 /proc/loadavg)"
    [ $rc = 0 ] && pass=$((pass + 1)) || grep '^FAIL' -A3 <<<"$out"
done
echo "soak: $pass of $runs runs passed"
[ "$pass" = "$runs" ]
