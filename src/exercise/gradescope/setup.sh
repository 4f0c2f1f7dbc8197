#!/bin/sh
# setup.sh - Gradescope's image set-up for tristep's autograder (make
# gradescope): the packages the judge and the sandbox need, then the judge
# and the lesson's student library built once, in /autograder/source.
set -eu
root=${AUTOGRADER_ROOT:-/autograder}
cd "$root/source"
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends build-essential make git >/dev/null
sh src/deps.sh build
sh src/deps.sh grade
make -s grade-build LESSON=@LESSON@
