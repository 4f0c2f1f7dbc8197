#!/bin/sh
# grade.sh - `make grade LESSON=NN DIR=submissions/`: the lesson's checks on
# every student .c file of a folder, each file compiled, linked and checked
# in a process of its own under a time limit, one CSV row per file. A file
# that does not compile, does not link, crashes or never finishes gets its
# row with that verdict and the run goes on to the next file.
#
# The Makefile passes what it knows about the build in the environment:
#   GRADE_LESSON  the lesson number, NN
#   GRADE_DIR     the folder of the students' files
#   GRADE_OUT     the folder of the grading run (a folder per file in it)
#   GRADE_CSV     the CSV to write
#   GRADE_TIME    seconds one file's checks may take
#   GRADE_CC      the command that compiles a student file (make check's)
#   GRADE_LD      the command that links, GRADE_OBJS what it links with the
#                 student's object, GRADE_LIBS the libraries
#
# Per file F (stem S) the run keeps, in GRADE_OUT/S/: compile.txt (the
# compiler's messages), check.txt (what `exercise-NN --check` printed) and
# the counterexample that the check writes (in its own folder, so that two
# files never overwrite each other's).
#
# The CSV: file, result (pass, fail, compile error, link error, crashed,
# timed out), checks passed, checks in all, then one column per check of
# the lesson (ok, FAILED, crashed, timed out, or empty when it did not
# run), the first failure and the counterexample's path.
set -u

nn=$GRADE_LESSON
dir=${GRADE_DIR%/}
out=$GRADE_OUT
csv=$GRADE_CSV
limit=${GRADE_TIME:-60}

[ -d "$dir" ] || { echo "DIR=$dir: no such folder" >&2; exit 2; }
mkdir -p "$out" || exit 1

# a CSV field: quoted, inner quotes doubled
field() { printf '"%s"' "$(printf '%s' "$1" | sed 's/"/""/g')"; }

files=$(find "$dir" -maxdepth 1 -type f -name '*.c' | LC_ALL=C sort)
# the file list splits at newlines only (a name may hold a space); the
# commands of the Makefile split at spaces, as usual
nl='
'
ws=" 	$nl"
[ -n "$files" ] || { echo "DIR=$dir holds no .c file" >&2; exit 2; }

# Run every file; keep per file: result, passed, total, first failure,
# counterexample (in GRADE_OUT/S/row).
IFS=$nl
for f in $files; do
    IFS=$ws
    stem=$(basename "$f" .c | tr -c 'A-Za-z0-9_.\n-' '_')
    d=$out/$stem
    rm -rf "$d" && mkdir -p "$d" || exit 1
    result= passed=0 total= first= cx=
    printf 'grade %s: ' "$f"
    if ! $GRADE_CC -c "$f" -o "$d/student.o" > "$d/compile.txt" 2>&1; then
        result="compile error"
        first=$(grep -m1 'error' "$d/compile.txt")
    elif ! $GRADE_LD $GRADE_OBJS "$d/student.o" $GRADE_LIBS -o "$d/exercise-$nn" >> "$d/compile.txt" 2>&1; then
        result="link error"
        first=$(grep -m1 -i 'undefined\|error' "$d/compile.txt")
    else
        timeout -s KILL "$limit" "$d/exercise-$nn" --check --file "$f" --out "$d/check" \
            ${GRADE_VARIANT:+--exercise-variant "$GRADE_VARIANT"} \
            --open "make exercise LESSON=$nn${GRADE_VARIANT:+ VARIANT=$GRADE_VARIANT} FILE=$f" > "$d/check.txt" 2>&1 < /dev/null
        st=$?
        total=$(sed -n 's#^  [0-9][0-9]*/\([0-9][0-9]*\) .*#\1#p' "$d/check.txt" | head -n 1)
        passed=$(grep -c '^  [0-9][0-9]*/[0-9][0-9]* .* ok (' "$d/check.txt")
        first=$(sed -n 's#^  [0-9][0-9]*/[0-9][0-9]* \(.*[^ ]\)  *\(FAILED\|CRASHED\|DID NOT FINISH\)$#\1#p' \
                "$d/check.txt" | head -n 1)
        cx=$(find "$d/check" -name '*.scene' 2>/dev/null | head -n 1)
        if [ "$st" -eq 0 ]; then
            result=pass
        elif [ "$st" -eq 137 ] || [ "$st" -eq 124 ]; then
            result="timed out"
            # the check it was in: the last one started, with no verdict
            [ -n "$first" ] || first=$(grep '^  [0-9][0-9]*/[0-9][0-9]* ' "$d/check.txt" | tail -n 1 |
                                       sed -n 's#^  [0-9][0-9]*/[0-9][0-9]* ##p' | sed 's/  .*//; s/ *$//')
            [ -n "$first" ] || first="no verdict within $limit s"
        elif grep -q 'DID NOT FINISH$' "$d/check.txt"; then
            result="timed out"
        elif grep -q 'CRASHED$' "$d/check.txt" || [ "$st" -gt 128 ]; then
            result=crashed
        else
            result=fail
        fi
    fi
    echo "$result"
    printf '%s\n%s\n%s\n%s\n%s\n%s\n' "$f" "$result" "$passed" "$total" "$first" "$cx" > "$d/row"
done

# The lesson's checks, by number, from whatever the runs printed (a file
# that passes prints them all; a failing one up to its failure).
names=$(cat "$out"/*/check.txt 2>/dev/null |
        sed -n 's#^  \([0-9][0-9]*\)/[0-9][0-9]* \(.*[^ ]\)  *\(ok (.*\|FAILED\|CRASHED\|DID NOT FINISH\)$#\1 \2#p' | LC_ALL=C sort -n -u -k1,1)
n=0
IFS=$nl
for f in $files; do
    IFS=$ws
    t=$(sed -n 4p "$out/$(basename "$f" .c | tr -c 'A-Za-z0-9_.\n-' '_')/row")
    [ -n "$t" ] && [ "$t" -gt "$n" ] && n=$t
done

tmp=$csv.tmp
{
    printf 'file,result,passed,checks'
    i=1
    while [ "$i" -le "$n" ]; do
        name=$(printf '%s\n' "$names" | sed -n "s/^$i //p" | head -n 1)
        printf ',%s' "$(field "${name:-check $i}")"
        i=$((i + 1))
    done
    printf ',first failure,counterexample\n'
    IFS=$nl
for f in $files; do
    IFS=$ws
        d=$out/$(basename "$f" .c | tr -c 'A-Za-z0-9_.\n-' '_')
        { read -r file; read -r result; read -r passed; read -r total; read -r first; read -r cx; } < "$d/row"
        printf '%s,%s,%s,%s' "$(field "$file")" "$(field "$result")" "${passed:-0}" "${total:-$n}"
        i=1
        while [ "$i" -le "$n" ]; do
            v=
            if [ -f "$d/check.txt" ]; then
                line=$(grep "^  $i/[0-9][0-9]* " "$d/check.txt" | head -n 1)
                case $line in
                    *" ok ("*) v=ok ;;
                    *FAILED) v=FAILED ;;
                    *CRASHED) v=crashed ;;
                    *"DID NOT FINISH") v="timed out" ;;
                    ?*) [ "$result" = "timed out" ] && v="timed out" ;;
                esac
            fi
            printf ',%s' "$v"
            i=$((i + 1))
        done
        printf ',%s,%s\n' "$(field "$first")" "$(field "$cx")"
    done
} > "$tmp" && mv "$tmp" "$csv" || exit 1
echo "grade: $(printf '%s\n' "$files" | wc -l | tr -d ' ') files, the table in $csv"
