#!/usr/bin/env bash
# packaging/mkdeb.sh: `make deb` — a Debian package of this tree's build, with dpkg-deb and
# no network: build/rastty_VERSION_ARCH.deb (its path printed last).
#   /usr/lib/rastty/rastty          the binary (built for any prefix: it finds its assets
#   /usr/lib/rastty/assets/         in assets/ beside itself, so no rebuild is needed)
#   /usr/bin/rastty -> ../lib/rastty/rastty
#   /usr/share/man/man1/rastty.1.gz, /usr/share/doc/rastty/README.md
# Depends: the packages that own the shared libraries the binary links (dpkg -S on ldd's
# list), as dpkg-shlibdeps would name them, without versions.
set -eu
cd "$(dirname "$0")/.."
BIN=${RASTTY_BIN:-./rastty}
version=$(sed -n 's/^#define RASTTY_VERSION "\(.*\)"/\1/p' src/main.c)
arch=$(dpkg --print-architecture)
stage=build/deb/rastty_${version}_${arch}
rm -rf "$stage"
install -d "$stage/DEBIAN" "$stage/usr/bin" "$stage/usr/lib/rastty/assets" \
    "$stage/usr/share/man/man1" "$stage/usr/share/doc/rastty"
install -m 755 "$BIN" "$stage/usr/lib/rastty/rastty"
ln -s ../lib/rastty/rastty "$stage/usr/bin/rastty"
install -m 644 $(ls assets/*.obj assets/*.mtl assets/*.png assets/demo.rsc) "$stage/usr/lib/rastty/assets/"
gzip -9n < man/rastty.1 > "$stage/usr/share/man/man1/rastty.1.gz"
chmod 644 "$stage/usr/share/man/man1/rastty.1.gz"
install -m 644 README.md "$stage/usr/share/doc/rastty/README.md"
deps=$(ldd "$BIN" | awk '/=> \// { print $3 }' | while read -r lib; do
           dpkg -S "$(readlink -f "$lib")" 2>/dev/null || dpkg -S "$lib" 2>/dev/null || true
       done | cut -d: -f1 | sort -u | paste -sd, | sed 's/,/, /g')
size=$(du -sk "$stage" | cut -f1)
cat > "$stage/DEBIAN/control" <<CONTROL
Package: rastty
Version: $version
Architecture: $arch
Maintainer: rastty developers <rastty@localhost>
Installed-Size: $size
Depends: $deps
Section: graphics
Priority: optional
Description: software rasterizer that draws 3D models in a terminal
 rastty renders OBJ, STL, PLY, glTF and other models on the CPU and shows them in
 the terminal as coloured half blocks (or quadrant, sextant, braille, ASCII cells),
 with an interactive viewer paced for slow links, and writes PNG, PPM and ANSI files.
CONTROL
out=build/rastty_${version}_${arch}.deb
dpkg-deb --root-owner-group --build "$stage" "$out" > /dev/null
echo "$out"
