#!/bin/sh
# kit.sh - a student kit, and what a tree without the answers leaves out.
#
#   kit.sh write KIT FILE...     (make student-kit) this tree into folder KIT
#                                without what gives the answers away; FILE...
#                                the test files that need the answers
#   kit.sh left-out FILE...      (make test, in a tree without the answers)
#                                say which tests were left out, and why
#
# What a kit leaves out:
#   - every lesson's worked answers, lessons/NN-name/answer.c and the graded
#     variants' answer-V.c, and its answer key, ANSWERS.md;
#   - the mutation suite, tests/mutations/ (each patch quotes an answer);
#   - the test files that need the answers (FILE..., the Makefile's
#     NEED_ANSWERS), and in the other test files every block
#
#         #if !TRISTEP_NO_ANSWERS
#         ...                          a test, or a part of one, that needs
#         #endif                       an answer key or quotes its numbers
#
#     (the Makefile defines TRISTEP_NO_ANSWERS when the answers are absent,
#     so a tree whose answers were removed by hand leaves the same out).
# Each is named in the kit's tests/left-out.txt, which make test there
# prints. The files come from git (the files it tracks) or, outside a git
# checkout, from the tree itself without its build folders; their times are
# kept.
set -eu
mode=$1
shift

# The tests of the blocks above in a test file: the Test( a block holds,
# or the one it sits in; one "suite/name" a line.
blocks() {
    awk '
        /^Test\(/ { t = $0; sub(/^Test\( */, "", t); split(t, a, /[ ,)]+/); t = a[1] "/" a[2] }
        /^#if !TRISTEP_NO_ANSWERS$/ { inblock = 1; whole = 0; outer = t; next }
        inblock && /^Test\(/ { whole = 1 }
        inblock && /^#endif/ { inblock = 0
                               if (whole) print t "  (the whole test)"
                               else print outer "  (its answer-key part)"; next }
    ' "$1"
}

# What was left out, counted: "N test files and M tests".
counted() {
    files=$(grep -c '(the whole file)' "$1" || true)
    tests=$(grep -vc '(the whole file)' "$1" || true)
    echo "$files test file$([ "$files" = 1 ] || echo s) and $tests test$([ "$tests" = 1 ] || echo s)"
}

if [ "$mode" = left-out ]; then
    list=tests/left-out.txt
    if [ ! -f "$list" ]; then   # the answers removed by hand: the same, found in the tree
        list=$(mktemp "${TMPDIR:-/tmp}/tristep-left-out.XXXXXX")
        trap 'rm -f "$list"' EXIT
        for f in "$@"; do [ -f "$f" ] && echo "$f  (the whole file)"; done > "$list"
        for f in tests/*.c; do blocks "$f" | sed "s#^#$f: #"; done >> "$list"
    fi
    echo "make test left out $(counted "$list") (or parts of tests), which need the answers"
    echo "this tree does not hold (lessons/*/answer.c, ANSWERS.md, tests/mutations/); none was run or counted:"
    sed 's/^/  /' "$list"
    exit 0
fi

[ "$mode" = write ] || { echo "kit.sh: write KIT FILE... | left-out FILE..." >&2; exit 2; }
kit=$1
shift
case $kit in
    ""|/) echo "make student-kit: KIT=$kit is not a folder to write" >&2; exit 2 ;;
esac
if [ -e "$kit" ] && [ -n "$(ls -A "$kit" 2>/dev/null)" ] && [ ! -f "$kit/tests/left-out.txt" ]; then
    echo "make student-kit: $kit exists and is not a student kit; give an empty or new folder" >&2
    exit 2
fi
need=" $* "
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tristep-kit.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
    git ls-files > "$tmp/all"
else
    find . \( -name 'build*' -o -name .git \) -prune -o -type f -print | sed 's#^\./##' | sort > "$tmp/all"
fi
: > "$tmp/keep"
: > "$tmp/left"
while IFS= read -r f; do
    [ -f "$f" ] || continue     # tracked, but removed from the tree
    case $f in
        lessons/*/answer.c|lessons/*/answer-*.c|lessons/*/ANSWERS.md|tests/mutations/*) continue ;;
    esac
    case $need in
        *" $f "*) echo "$f  (the whole file)" >> "$tmp/left"; continue ;;
    esac
    echo "$f" >> "$tmp/keep"
done < "$tmp/all"

rm -rf "$kit"
mkdir -p "$kit"
tar -cf - -T "$tmp/keep" | tar -xf - -C "$kit"
# the blocks that need the answers, out of the test files that keep the rest
for f in $(grep -l '^#if !TRISTEP_NO_ANSWERS$' $(grep '^tests/.*\.c$' "$tmp/keep") 2>/dev/null); do
    blocks "$f" | sed "s#^#$f: #" >> "$tmp/left"
    awk '/^#if !TRISTEP_NO_ANSWERS$/ { skip = 1; next } skip && /^#endif/ { skip = 0; next } !skip' \
        "$f" > "$kit/$f"
    touch -r "$f" "$kit/$f"
done
cp "$tmp/left" "$kit/tests/left-out.txt"
echo "student kit in $kit: $(grep -c . "$tmp/keep") files; left out the worked answers" \
     "($(grep -c '^lessons/.*/answer' "$tmp/all" || true) files), the answer keys ($(grep -c '^lessons/.*/ANSWERS.md$' "$tmp/all" || true))," \
     "the mutation suite ($(grep -c '^tests/mutations/' "$tmp/all" || true) patches) and $(counted "$tmp/left") (tests/left-out.txt)"
