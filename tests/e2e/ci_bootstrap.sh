#!/usr/bin/env bash
# ci_bootstrap.sh: `.ci/run` on a bare image (no make, no pkg-config) installs both before its
# first make, and the Makefile says nothing about a missing pkg-config. apt-get and make are
# stubs that log what they were asked to do; nothing is installed for real.
source "$(dirname "$0")/lib/common.sh"

STUB=$(cd "$OUT" && pwd)/bin
LOG=$(cd "$OUT" && pwd)/log.txt
mkdir -p "$STUB"
for tool in dirname id cat; do ln -sf "$(command -v $tool)" "$STUB/$tool"; done
# apt-get "installs" make and pkg-config as logging stubs
cat > "$STUB/apt-get" <<STUBEOF
#!/bin/bash
echo "apt-get \$*" >> "$LOG"
for p in "\$@"; do
    case \$p in make|pkg-config)
        printf '#!/bin/bash\necho "%s \$*" >> "%s"\n' "\$p" "$LOG" > "$STUB/\$p"
        /bin/chmod +x "$STUB/\$p" ;;
    esac
done
STUBEOF
chmod +x "$STUB/apt-get"

bare_image() {
    rm -f "$LOG" "$STUB/make" "$STUB/pkg-config"
    env -i PATH="$STUB" CI=true /bin/bash .ci/run < /dev/null; local rc=$?
    echo "exit $rc; log:"; cat "$LOG"
    [ $rc -eq 0 ] || return 1
    # the first make comes after an apt-get install naming make and pkg-config
    local first_make install
    first_make=$(grep -n '^make ' "$LOG" | head -1 | cut -d: -f1)
    install=$(grep -n '^apt-get install.* make' "$LOG" | grep pkg-config | head -1 | cut -d: -f1)
    [ -n "$install" ] && [ -n "$first_make" ] && [ "$install" -lt "$first_make" ] || return 1
    grep -q '^make deps' "$LOG" && grep -q '^make test' "$LOG"
}
check ci_run_bootstraps_make_and_pkg_config bare_image

# make with no pkg-config on PATH: no "pkg-config: No such file or directory" on stderr
no_pkg_config_noise() {
    local dir=$OUT/nopc; mkdir -p "$dir"
    for tool in make sh cc; do ln -sf "$(command -v $tool)" "$dir/$tool"; done
    env -i PATH="$dir" make -n help > /dev/null 2> "$OUT/make.err"
    echo "stderr: $(cat "$OUT/make.err")"
    ! grep -q pkg-config "$OUT/make.err"
}
check makefile_quiet_without_pkg_config no_pkg_config_noise

finish
