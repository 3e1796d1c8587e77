#!/usr/bin/env bash
# ci_bootstrap.sh: `.ci/run` on a bare image (no make, no pkg-config) installs both before its
# first make, and the Makefile says nothing about a missing pkg-config; the README's first two
# lines work verbatim as root without sudo and as a user with sudo, and `make deps` installs
# the build's and the tests' packages (groff for the man-page check). apt-get and make are
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

# The README's first two lines (its first ```sh block), verbatim, on a fresh machine: as root
# where there is no sudo (a minimal Debian), and as a user with sudo. apt-get, make, sudo and
# ./rastty are logging stubs; each line runs in its own shell, as typed.
readme_lines() { awk '/^```sh$/ { on = 1; next } on && /^```$/ { exit } on' README.md; }
stub() { # stub DIR NAME [exec]: NAME logs its arguments (and with exec, runs them)
    printf '#!/bin/bash\necho "%s $*" >> "%s"\n%s\n' "$2" "$LOG" "${3:+exec \"\$@\"}" > "$1/$2"
    chmod +x "$1/$2"
}
# setup WITH_SUDO: run both lines; the log in $LOG
setup() {
    local dir=$PWD/$OUT/setup-$1 line n=0
    rm -rf "$dir"; mkdir -p "$dir/bin" "$dir/work"
    rm -f "$LOG"
    stub "$dir/bin" apt-get; stub "$dir/bin" make; stub "$dir/work" ./rastty
    [ "$1" = sudo ] && stub "$dir/bin" sudo exec
    ln -sf "$(command -v bash)" "$dir/bin/bash"
    [ "$(readme_lines | wc -l)" -eq 2 ] || { echo "README's first block is not two lines:"; readme_lines; return 1; }
    while IFS= read -r line; do
        n=$((n + 1))
        (cd "$dir/work" && env -i PATH="$dir/bin" HOME="$dir" bash -c "$line") > "$dir/out$n" 2>&1 ||
            { echo "line $n failed: $line"; cat "$dir/out$n"; return 1; }
    done < <(readme_lines)
    echo "log:"; cat "$LOG"
}
readme_as_root() {
    setup root || return 1
    ! grep -q sudo "$LOG" || return 1
    [ "$(sed 's/ .*//' "$LOG" | tr '\n' ' ')" = "apt-get apt-get make ./rastty make make " ] || return 1
    grep -qx 'apt-get update' "$LOG" && grep -q '^apt-get install -y build-essential' "$LOG" &&
        grep -qx 'make deps' "$LOG" && grep -qx 'make test' "$LOG"
}
check readme_setup_lines_work_as_root_without_sudo readme_as_root
readme_as_user() {
    setup sudo || return 1
    # root's work under sudo (apt-get, make deps), the build and the tests as the user
    grep -qx 'sudo apt-get update' "$LOG" && grep -q '^sudo apt-get install -y build-essential' "$LOG" &&
        grep -qx 'sudo make deps' "$LOG" && grep -qx 'make test' "$LOG" &&
        ! grep -q '^sudo make test\|^sudo make$\|^sudo ./rastty' "$LOG"
}
check readme_setup_lines_work_as_a_user_with_sudo readme_as_user

# make deps as root installs what the build needs (line 1's packages) and what the tests
# need, groff for docs.sh's man-page check among them; apt-get and id are stubs
deps_installs() {
    local dir=$OUT/deps p
    rm -rf "$dir"; mkdir -p "$dir"; rm -f "$LOG"
    stub "$dir" apt-get
    printf '#!/bin/sh\necho 0\n' > "$dir/id"; chmod +x "$dir/id"
    PATH="$dir:$PATH" make -s deps > /dev/null || return 1
    echo "log:"; cat "$LOG"
    local install; install=$(grep '^apt-get install' "$LOG")
    for p in groff-base tmux libosmesa6-dev chafa python3 \
             $(readme_lines | head -1 | sed -E 's/.*apt-get install -y ([^&]*)&&.*/\1/'); do
        [[ " $install " == *" $p "* ]] || { echo "make deps does not install $p"; return 1; }
    done
}
check make_deps_installs_the_build_and_test_packages deps_installs

finish
