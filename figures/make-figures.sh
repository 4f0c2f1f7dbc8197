#!/bin/sh
# make-figures.sh BUILD [OUT] - regenerate every figure named in figures/list
# into OUT (default: the folder of this script) with the programs in BUILD.
#
# One process per figure: cairo numbers the ids inside an SVG per process, so
# two figures drawn by one process would not come out byte for byte the same.
set -eu
build=${1:?usage: make-figures.sh BUILD [OUT]}
here=$(dirname "$0")
out=${2:-$here}
grep -v -e '^[[:space:]]*#' -e '^[[:space:]]*$' "$here/list" |
while read -r name lesson scene step view size extra; do
    # $extra is split on purpose: it holds zero or more options
    # shellcheck disable=SC2086
    "$build/$lesson" --figure "$out/$name" --scene "$scene" --step "$step" \
        --view "$view" --size "$size" $extra ||
        { echo "figures/list: $name: $build/$lesson failed" >&2; exit 1; }
done
