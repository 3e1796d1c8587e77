#!/usr/bin/env bash
# docs.sh: the documentation keeps up with the code — every --flag that --help lists is in
# man/rastty.1, and the man page formats without warnings.
source "$(dirname "$0")/lib/common.sh"

flags_in_man() {
    local missing=0
    for f in $("$BIN" --help | grep -oE -- '--[a-z][a-z0-9-]*' | sort -u); do
        grep -qF -- "$(printf '%s' "$f" | sed 's/-/\\-/g')" man/rastty.1 ||
            { echo "not in man/rastty.1: $f"; missing=1; }
    done
    return $missing
}
check every_help_flag_is_in_the_man_page flags_in_man
man_clean() {
    command -v groff >/dev/null || return 0
    local warn
    warn=$(groff -man -Tutf8 -ww man/rastty.1 2>&1 >/dev/null)
    [ -z "$warn" ] || { echo "$warn"; return 1; }
}
if command -v groff >/dev/null; then
    check man_page_formats_without_warnings man_clean
else
    skip man_page_formats_without_warnings "groff is not installed"
fi
# The man page says what the code does (issue 25: FILES said half blocks were the only glyph
# set, PLY said vertex colours were not drawn): every --glyphs value of --help is in the man
# page's config line for glyphs, and no "not yet" promise is left in it.
man_current() {
    local sets line g
    sets=$("$BIN" --help | grep -oE -- '--glyphs G +how cells show pixels: [a-z|]+' | sed 's/.*: //')
    [ -n "$sets" ] || { echo "no --glyphs values in --help"; return 1; }
    line=$(grep -A1 '^\.B glyphs = ' man/rastty.1 | head -1)
    for g in ${sets//|/ }; do
        [[ $line == *" $g"* ]] || { echo "man FILES glyphs line lacks $g: $line"; return 1; }
    done
    ! grep -n 'not yet\|the only way so far' man/rastty.1
}
check man_page_says_what_the_code_does man_current
finish
