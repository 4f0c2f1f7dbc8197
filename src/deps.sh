#!/bin/sh
# deps.sh MODE [OUT] - the Makefile's dependency step.
#
# Finds the system packages tristep needs; on Debian or Ubuntu installs the
# missing ones with apt-get (through sudo when not root) and says so; on any
# other system prints the packages to install and fails. MODE is what is
# about to be built:
#   build   SDL2, cairo, Pango, DejaVu fonts  (make, make run, make figures)
#   test    everything make test runs, in one apt-get run: the above,
#           Criterion, Xvfb, xdotool, ImageMagick's import, patch (the
#           mutation suite), bubblewrap (make grade), and what simde and
#           aarch64 need
#   bench   the build packages and OSMesa for the llvmpipe peer  (make bench)
#   fuzz    the test packages, clang and its libFuzzer  (make fuzz)
#   grade   the build packages, bubblewrap (the sandbox of make grade), zip
#           and unzip (make gradescope)
#           (make test grades too: its packages include bubblewrap)
#   simde   SIMDe's headers  (make simde-test: the exactness driver through SIMDe)
#   aarch64 Debian's aarch64 cross compiler and C library, qemu-user, SIMDe  (make aarch64)
# With OUT, writes the compiler and linker flags as a makefile fragment
# (none for simde and aarch64: the core and the lessons use only libc and libm).
#
# Installs never race: one run of this script installs at a time (it holds
# a lock on this file while it installs; a second run waits and then finds
# the packages there). A dry run of make (make -n, -q or -t: make still runs
# this script to remake the fragment it includes) installs nothing: it says
# what is missing and writes the fragment if it can.
set -eu
mode=${1:-build}
out=${2:-}

case $mode in
  build) groups=build ;;
  test)  groups="build test grade simde aarch64" ;;
  bench) groups="build bench" ;;
  fuzz)  groups="build test fuzz" ;;
  grade) groups="build grade" ;;
  simde|aarch64) groups=$mode ;;
  *) echo "deps.sh: unknown mode $mode (build, test, bench, fuzz, grade, simde, aarch64)" >&2; exit 2 ;;
esac

# The Debian packages and the plain names of a group.
debs() {
  case $1 in
    build)   echo "pkg-config libsdl2-dev libcairo2-dev libpango1.0-dev fonts-dejavu-core" ;;
    test)    echo "libcriterion-dev xvfb xdotool imagemagick patch" ;;
    bench)   echo "libosmesa6-dev" ;;
    fuzz)    echo "clang libclang-rt-dev" ;;
    grade)   echo "bubblewrap zip unzip" ;;
    simde)   echo "libsimde-dev" ;;
    aarch64) echo "gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user libsimde-dev" ;;
  esac
}
names() {
  case $1 in
    build)   echo "SDL2, cairo, Pango (with pangocairo), DejaVu fonts, pkg-config" ;;
    test)    echo "Criterion, Xvfb, xdotool, ImageMagick, patch" ;;
    bench)   echo "OSMesa (Mesa)" ;;
    fuzz)    echo "clang with its libFuzzer runtime" ;;
    grade)   echo "bubblewrap (bwrap), the sandbox of make grade; zip and unzip (make gradescope)" ;;
    simde)   echo "SIMDe (SIMD Everywhere, header-only)" ;;
    aarch64) echo "Debian's or Ubuntu's aarch64 cross compiler, qemu-user and SIMDe" ;;
  esac
}

# What of a group is missing, as a list of words (empty: nothing).
has() { command -v "$1" >/dev/null 2>&1 || printf '%s ' "$1"; }
pc() {
  if command -v pkg-config >/dev/null 2>&1; then
    for p; do pkg-config --exists "$p" || printf '%s ' "$p"; done
  else printf 'pkg-config '; fi
}
missing_of() {
  case $1 in
    build)
      pc sdl2 cairo pangocairo
      [ -f /usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf ] || printf 'fonts-dejavu ' ;;
    test)
      pc criterion; has Xvfb; has xdotool; has import; has patch ;;
    bench)
      pc osmesa ;;
    grade)
      has bwrap; has zip; has unzip ;;
    fuzz)    # clang, and a program linked with libFuzzer
      printf 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n) { return !d + !n; }\n' |
        clang -fsanitize=fuzzer -x c - -o /dev/null >/dev/null 2>&1 || printf 'clang+libFuzzer ' ;;
    simde)   # SIMDe's headers where the compiler finds them
      printf '#include <simde/x86/sse2.h>\n' | ${CC:-cc} -E -x c - >/dev/null 2>&1 || printf 'SIMDe ' ;;
    aarch64)
      has aarch64-linux-gnu-gcc; has qemu-aarch64
      [ -f /usr/aarch64-linux-gnu/lib/libc.a ] || printf 'libc6-dev-arm64-cross '
      [ -f /usr/include/simde/x86/sse2.h ] || printf 'SIMDe ' ;;
  esac
}
# the words of the standard input, each once, in order
once() { tr ' ' '\n' | awk 'NF && !seen[$0]++' | paste -sd' ' -; }
missing() { for g in $groups; do missing_of "$g"; done | once; }
deb=$(for g in $groups; do debs "$g"; done | once)

# A dry run of make: TRISTEP_DRY_RUN from the Makefile (make takes -n
# out of MAKEFLAGS while it remakes an included makefile), or, in a recipe
# make -n runs anyway, the first word of MAKEFLAGS, make's one-letter
# options (it starts with a space when there are none).
dry=${TRISTEP_DRY_RUN-}
case ${MAKEFLAGS-} in
  [!\ -]*) case ${MAKEFLAGS%% *} in *[nqt]*) dry=1 ;; esac ;;
esac

need=$(missing)
if [ -n "$need" ] && [ -n "$dry" ]; then
  echo "tristep: missing $need; a dry run (make -n) installs nothing (make would install: $deb)" >&2
elif [ -n "$need" ] && [ -r /etc/debian_version ] && command -v apt-get >/dev/null 2>&1; then
  if [ -z "${TRISTEP_DEPS_LOCKED-}" ] && command -v flock >/dev/null 2>&1; then
    # one install at a time; the one that waited checks again, then
    # finds what the other installed
    flock -n "$0" true || echo "tristep: another make is installing packages; waiting for it ($0 is locked)"
    TRISTEP_DEPS_LOCKED=1 exec flock "$0" sh "$0" "$@"
  fi
  sudo=; [ "$(id -u)" -eq 0 ] || sudo=sudo
  echo "tristep: missing $need; installing Debian packages: $deb"
  # and wait for the package system when something else (apt, an
  # automatic update) holds it
  $sudo apt-get -o DPkg::Lock::Timeout=600 update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get -o DPkg::Lock::Timeout=600 install -y -qq \
    --no-install-recommends $deb >/dev/null
  need=$(missing)
  [ -z "$need" ] || { echo "tristep: still missing after apt-get: $need" >&2; exit 1; }
elif [ -n "$need" ]; then
  echo "tristep: missing $need. Please install: $(for g in $groups; do names "$g"; done | paste -sd';' - | sed 's/;/; /g')." >&2
  echo "  Debian/Ubuntu: apt-get install $deb" >&2
  case $mode in
    aarch64) echo "  (the aarch64 target uses Debian's cross packages; on an ARM64 machine, make test runs natively)" >&2 ;;
    grade) echo "  Fedora: dnf install bubblewrap zip unzip; Arch: pacman -S bubblewrap zip unzip" >&2
           echo "  (make grade's sandbox needs Linux's namespaces; where it cannot run, make grade UNSAFE=1" >&2
           echo "  grades without isolation, and its CSV says so)" >&2 ;;
    simde) echo "  Fedora: dnf install simde-devel" >&2
           echo "  macOS (Homebrew): brew install simde" >&2 ;;
    *) echo "  Fedora: dnf install pkgconf SDL2-devel cairo-devel pango-devel dejavu-sans-mono-fonts criterion-devel simde-devel xorg-x11-server-Xvfb xdotool ImageMagick patch bubblewrap zip unzip mesa-libOSMesa-devel (Fedora 43 on: mesa-compat-libOSMesa-devel)" >&2
       echo "  macOS (Homebrew): brew install pkg-config sdl2 cairo pango criterion simde; brew install --cask font-dejavu (no OSMesa: make bench runs without the llvmpipe peer)" >&2 ;;
  esac
  exit 1
fi

[ -n "$out" ] || exit 0
mkdir -p "$(dirname "$out")"
case " $groups " in
  *" build "*)
    flags=$(pkg-config --cflags sdl2 cairo pangocairo 2>/dev/null) && libs=$(pkg-config --libs sdl2 cairo pangocairo) ||
      { echo "tristep: cannot write $out without the packages above" >&2; exit 2; }
    {
      echo "# written by src/deps.sh: flags of the system libraries"
      echo "PKG_CFLAGS := $flags"
      echo "PKG_LIBS := $libs -lm"
    } > "$out.tmp" ;;
  *) echo "# written by src/deps.sh: $mode needs no system library beyond libc and libm" > "$out.tmp" ;;
esac
mv "$out.tmp" "$out"
