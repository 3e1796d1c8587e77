#!/usr/bin/env bash
# deb.sh (issue 25): `make deb`'s package (packaging/mkdeb.sh, dpkg-deb, no network) installs
# and removes cleanly — into a private dpkg root (dpkg --root, never the machine's own): the
# binary, its assets, the man page; the installed rastty runs, finds its demo scene from
# anywhere and opens the viewer on it; removal leaves nothing but dpkg's own records.
source "$(dirname "$0")/lib/common.sh"

if ! command -v dpkg-deb >/dev/null || ! command -v dpkg >/dev/null; then
    skip debian_package_installs_runs_and_removes "dpkg not installed"
    finish
fi
if [ -n "${RASTTY_ASAN:-}" ]; then # the package is of the plain build
    skip debian_package_installs_runs_and_removes "packages the plain build, not the ASan one"
    finish
fi
# dpkg refuses a user other than root even for a private --root unless told (CI may run the
# suite as a user with sudo)
not_root=(); [ "$(id -u)" = 0 ] || not_root=(--force-not-root)
deb_cycle() {
    local root=$PWD/$OUT/root deb
    deb=$(packaging/mkdeb.sh) || return 1
    echo "package: $deb"
    dpkg-deb -I "$deb" | grep -q '^ Package: rastty$' || return 1
    dpkg-deb -I "$deb" | grep -q '^ Depends: .*libncursesw6' || { echo "no ncurses in Depends"; return 1; }
    rm -rf "$root"; mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates"
    touch "$root/var/lib/dpkg/status"
    dpkg --root="$root" "${not_root[@]}" --force-depends --force-script-chrootless -i "$deb" > $OUT/install.txt 2>&1 ||
        { cat $OUT/install.txt; return 1; }
    local f
    for f in usr/bin/rastty usr/lib/rastty/rastty usr/lib/rastty/assets/demo.rsc \
             usr/lib/rastty/assets/teapot.obj usr/share/man/man1/rastty.1.gz; do
        [ -e "$root/$f" ] || { echo "not installed: /$f"; return 1; }
    done
    "$root/usr/bin/rastty" --version | grep -q '^rastty ' || return 1
    zcat "$root/usr/share/man/man1/rastty.1.gz" | grep -q '^\.SH KEYS' || return 1
    # the viewer from a folder with no assets/: the installed demo scene
    mkdir -p $OUT/elsewhere
    tm new-session -d -s deb -x 100 -y 30 -c "$PWD/$OUT/elsewhere" \
        "env -u RASTTY_ASSETS $root/usr/bin/rastty --colors truecolor --no-spin; echo EXIT=\$? > $PWD/$OUT/deb.exit; sleep 60"
    wait_for 15 hud_has deb "demo.rsc [1/1]" || { echo "no demo: $(status_line deb)"; return 1; }
    tm send-keys -t deb q
    wait_for 10 test -f $OUT/deb.exit && grep -q EXIT=0 $OUT/deb.exit || { echo "viewer exit: $(cat $OUT/deb.exit 2>/dev/null)"; return 1; }
    dpkg --root="$root" "${not_root[@]}" --force-script-chrootless -r rastty > $OUT/remove.txt 2>&1 || { cat $OUT/remove.txt; return 1; }
    local left; left=$(cd "$root" && find . -path ./var -prune -o -print | grep -v '^\.$')
    [ -z "$left" ] || { echo "left after removal:"; echo "$left"; return 1; }
}
check debian_package_installs_runs_and_removes deb_cycle
finish
