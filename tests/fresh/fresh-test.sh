#!/bin/bash
# fresh-test.sh - `make fresh-test`: the README's two commands on a
# brand-new Debian 12, as a newcomer runs them.
#
# A green make test on a developer's machine can hide a missing install
# step: what was installed by hand is still there. This builds a minimal
# Debian 12 (debootstrap --variant=minbase, plus git, make, gcc, libc6-dev
# and ca-certificates: nothing else), clones the repository's last commit
# into it and runs, with that system as their root:
#   make test                    the first run on that system must pass
#   make run                     under Xvfb, until lesson 01's window shows;
#                                then q closes it (exit status 0)
# It prints the packages the commands installed and the time each took.
#
# The base system is built once and kept as a tar file (FRESH_BASE, default
# /var/tmp/tristep-fresh-bookworm.tar); every run unpacks a new copy of it
# and removes it afterwards, nothing left mounted (FRESH_KEEP=1 keeps the
# copy and prints its path). FRESH_TIMEOUT (default 3600) is the seconds
# both commands may take.
#
# It needs root (debootstrap, chroot, mounts) and Debian's archive (the
# mirror of this machine's apt sources, or FRESH_MIRROR); without either it
# says so and exits 2.
set -u
# All of it is one function, read whole before it runs: a change to this
# file during a run cannot change the run.
main() {
say() { echo "fresh-test: $*"; }
die() { echo "fresh-test: $*" >&2; exit 2; }

[ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, chroot and mounts); run it as root (sudo make fresh-test)"
[ -r /etc/debian_version ] && command -v apt-get >/dev/null 2>&1 ||
  die "needs a Debian or Ubuntu machine (debootstrap and Debian's archive); this is not one"
repo=$(git rev-parse --show-toplevel 2>/dev/null) || die "run it inside a git checkout of tristep (it clones HEAD)"
base=${FRESH_BASE:-/var/tmp/tristep-fresh-bookworm.tar}
suite=bookworm

# Debian's archive: this machine's mirror
mirror=${FRESH_MIRROR:-$(awk '/^URIs:/ && $2 !~ /security/ {print $2; exit}' /etc/apt/sources.list.d/*.sources 2>/dev/null)}
[ -n "$mirror" ] || mirror=$(awk '$1 == "deb" && $2 !~ /security/ {print $2; exit}' /etc/apt/sources.list 2>/dev/null)
[ -n "$mirror" ] || die "no Debian mirror in /etc/apt/sources.list{,.d} (set FRESH_MIRROR)"
probe=$(mktemp)
if ! /usr/lib/apt/apt-helper download-file "$mirror/dists/$suite/Release" "$probe" >/dev/null 2>&1; then
  rm -f "$probe"
  die "Debian's archive is not reachable: $mirror/dists/$suite/Release (set FRESH_MIRROR)"
fi
rm -f "$probe"

# --- unmounting and removing, on every way out ------------------------------
dirs=()            # the systems to remove at the end (below /var/tmp)
keep=()            # ... or to keep (FRESH_KEEP=1)
# Every process whose root is below $1 ends; every mount below $1 is undone.
release() {
  local d=$1 p r t
  for p in /proc/[0-9]*; do
    r=$(readlink "$p/root" 2>/dev/null) || continue
    case $r in "$d"|"$d"/*) kill -KILL "${p#/proc/}" 2>/dev/null ;; esac
  done
  for t in $(findmnt -rn -o TARGET | grep "^$d/" | sort -r); do
    umount "$t" 2>/dev/null || umount -l "$t"
  done
}
child=             # the long command running, in the background (wait is
                   # interrupted by a signal, a command in the foreground is not)
cleanup() {
  local d
  [ -z "$child" ] || kill "$child" 2>/dev/null
  for d in "${dirs[@]}"; do
    release "$d"
    if findmnt -rn -o TARGET | grep -q "^$d/"; then
      echo "fresh-test: mounts remain under $d; not removed" >&2
    elif [ "${FRESH_KEEP:-0}" = 1 ] && [ "$d" = "${keep[0]-}" ]; then
      say "kept $d"
    else
      rm -rf --one-file-system "$d"
    fi
  done
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP      # through the EXIT trap

# --- the base system, once ----------------------------------------------------
if [ ! -s "$base" ]; then
  if ! command -v debootstrap >/dev/null 2>&1; then
    say "installing debootstrap on this machine"
    { apt-get install -y -qq debootstrap || { apt-get update -qq && apt-get install -y -qq debootstrap; }; } >/dev/null 2>&1 ||
      die "cannot install debootstrap"
  fi
  b=$(mktemp -d /var/tmp/tristep-fresh-base.XXXXXX)
  dirs+=("$b")
  chmod 755 "$b"                  # the system's /: apt's _apt user and others pass
  say "building a minimal Debian 12 with debootstrap from $mirror (once; kept as $base)"
  SECONDS=0
  debootstrap --variant=minbase --include=git,make,gcc,libc6-dev,ca-certificates \
    "$suite" "$b" "$mirror" >"$b.log" 2>&1 & child=$!
  if ! wait $child; then
    release "$b"
    tail -n 5 "$b.log" >&2
    die "debootstrap failed; whole log: $b.log"
  fi
  child=
  release "$b"                    # debootstrap leaves /proc or /sys mounted on some paths
  # the archive as a newly installed Debian 12 has it: the release, its
  # updates and the security updates
  { echo "deb $mirror $suite main"; echo "deb $mirror $suite-updates main"
    echo "deb http://deb.debian.org/debian-security $suite-security main"; } > "$b/etc/apt/sources.list"
  tar -cf "$base.part" -C "$b" . && mv "$base.part" "$base" || die "cannot write $base"
  rm -rf --one-file-system "$b" "$b.log"
  say "base system built in ${SECONDS}s"
fi

# Run a command with $1 as its root: in a mount namespace of its own whose
# root the system is (pivot_root), not a chroot. The kernel lets no
# chrooted process make a user namespace, and make grade's sandbox
# (bubblewrap, run as an unprivileged user) needs one, as on a real machine.
inside() {          # inside SECONDS ROOT COMMAND...: killed after SECONDS
  local t=$1; shift
  timeout -s KILL "$t" unshare --mount --fork --kill-child -- /bin/sh -c 'r=$1; shift
    mount --make-rprivate / && mount --rbind "$r" "$r" && cd "$r" && mkdir -p .oldroot &&
      pivot_root . .oldroot && umount -l /.oldroot && rmdir /.oldroot && exec "$@"' sh "$@"
}

# --- a new copy, the clone, the commands ---------------------------------------
root=$(mktemp -d /var/tmp/tristep-fresh.XXXXXX)
dirs+=("$root"); keep=("$root")
tar -xf "$base" -C "$root" || die "cannot unpack $base"
chmod 755 "$root"                 # the system's / (tar gives it the mode of the base's)
mount -t proc proc "$root/proc" && mount --bind /sys "$root/sys" && mount --bind /dev "$root/dev" &&
  mount --bind /dev/pts "$root/dev/pts" && mount -t tmpfs shm "$root/dev/shm" || die "cannot mount /proc, /sys, /dev in $root"
cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null
git clone -q "$repo" "$root/root/tristep" || die "cannot clone $repo"
head=$(git -C "$root/root/tristep" log --oneline -1)
say "$head, on a new Debian 12 (minbase, git, make, gcc, libc6-dev, ca-certificates)"
chroot "$root" dpkg-query -W -f '${Package}\n' | sort > "$root.before"

# Inside: make test, then make run under Xvfb until lesson 01's window shows.
cat > "$root/root/commands.sh" <<'EOF'
set -u
cd /root/tristep
t0=$SECONDS
echo "+ make test"
make test || { echo "fresh-test: make test failed after $((SECONDS - t0))s"; exit 1; }
echo "fresh-test: make test passed in $((SECONDS - t0))s"

t0=$SECONDS
for n in $(seq 70 99); do       # a free display (another Xvfb may hold one)
  [ -e /tmp/.X11-unix/X$n ] && continue
  Xvfb :$n -screen 0 1280x800x24 -nolisten tcp 2>/tmp/xvfb.err & xvfb=$!
  for i in $(seq 50); do [ -e /tmp/.X11-unix/X$n ] && break; kill -0 $xvfb 2>/dev/null || break; sleep 0.1; done
  [ -e /tmp/.X11-unix/X$n ] && kill -0 $xvfb 2>/dev/null && break
  xvfb=
done
[ -n "${xvfb-}" ] || { echo "fresh-test: no display for Xvfb"; cat /tmp/xvfb.err; exit 1; }
export DISPLAY=:$n
echo "+ make run   (DISPLAY=$DISPLAY)"
make run > /tmp/run.log 2>&1 & run=$!
win=
for i in $(seq 600); do
  win=$(xdotool search --onlyvisible --name . 2>/dev/null | head -n 1)
  [ -n "$win" ] && break
  kill -0 $run 2>/dev/null || break
  sleep 0.2
done
if [ -z "$win" ]; then
  echo "fresh-test: make run showed no window"; cat /tmp/run.log; kill $xvfb; exit 1
fi
name=$(xdotool getwindowname "$win")
geom=$(xdotool getwindowgeometry "$win" | sed -n 's/^ *Geometry: //p')
echo "fresh-test: make run opened the window \"$name\" ($geom) after $((SECONDS - t0))s"
sleep 1
import -display $DISPLAY -window root /tmp/window.png 2>/dev/null
xdotool mousemove --window "$win" 20 20 windowfocus "$win" key q
for i in $(seq 100); do kill -0 $run 2>/dev/null || break; sleep 0.1; done
kill -0 $run 2>/dev/null && { echo "fresh-test: the window did not close on q"; kill $run; }
wait $run; st=$?
kill $xvfb
cat /tmp/run.log
case $name in
  "tristep 01-"*) ;;
  *) echo "fresh-test: the window is not lesson 01's: \"$name\""; exit 1 ;;
esac
[ $st -eq 0 ] || { echo "fresh-test: make run exited $st after q"; exit 1; }
echo "fresh-test: make run closed on q with status 0"
EOF

log=$root.log
SECONDS=0
inside "${FRESH_TIMEOUT:-3600}" "$root" /usr/bin/env -i HOME=/root \
  PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin TERM=dumb LANG=C.UTF-8 \
  /bin/bash /root/commands.sh > "$log" 2>&1 & child=$!
wait $child
rc=$?
child=
took=$SECONDS
chroot "$root" dpkg-query -W -f '${Package}\n' | sort > "$root.after"
[ -s "$root/tmp/window.png" ] && cp "$root/tmp/window.png" "$root.png"

grep -e '^fresh-test:' -e '^tristep:' -e '^+ ' -e 'Synthesis' -e 'Error' -e 'error:' "$log" | tail -n 40
added=$(comm -13 "$root.before" "$root.after")
say "the commands installed $(echo "$added" | grep -c .) packages:"
echo "$added" | paste -sd' ' - | fold -s -w 100 | sed 's/^/  /'
[ -s "$root.png" ] && say "screenshot of the window: $root.png"
rm -f "$root.before" "$root.after"
if [ $rc -eq 0 ]; then
  say "passed in ${took}s: make test and make run on a brand-new Debian 12 ($head); whole log: $log"
else
  [ $rc -eq 137 ] && [ $took -ge "${FRESH_TIMEOUT:-3600}" ] && say "timed out after ${FRESH_TIMEOUT:-3600}s"
  say "FAILED (exit $rc) after ${took}s; whole log: $log"
  tail -n 30 "$log"
fi
exit $((rc == 0 ? 0 : 1))
}
main "$@"
