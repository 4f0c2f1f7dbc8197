#!/bin/sh
# unlinked.sh NN < linker-messages: a student's file that does not link
# against its lesson's student library (src/exercise/student-library.txt),
# said in plain words: each name it uses that the library does not give.
nn=$1
names=$(sed -n "s/.*undefined reference to \`\([^']*\)'.*/\1/p" | sort -u)
if [ -z "$names" ]; then
    echo "your file does not link (the linker's messages are above)"
    exit 0
fi
for n in $names; do
    echo "your file uses $n, which lesson $nn's exercise does not give (the student library holds only what the skeleton calls: src/exercise/student-library.txt)"
done
