#!/bin/sh
# deps.sh MODE OUT - the Makefile's dependency step.
#
# Finds the system packages tristep needs; on Debian or Ubuntu installs the
# missing ones with apt-get (through sudo when not root) and says so; on any
# other system prints the packages to install and fails. MODE is what is
# about to be built:
#   build   SDL2, cairo, Pango, DejaVu fonts  (make, make run, make figures)
#   test    the above, Criterion, Xvfb, xdotool and ImageMagick's import  (make test)
#   bench   the above, OSMesa for the llvmpipe peer  (make bench)
#   grade   bubblewrap, the sandbox of make grade
#   simde   SIMDe's headers  (make simde-test: the exactness driver through SIMDe)
#   aarch64 Debian's aarch64 cross compiler and C library, qemu-user, SIMDe  (make aarch64)
# With OUT, writes the compiler and linker flags as a makefile fragment
# (none for simde and aarch64: the core and the lessons use only libc and libm).
set -eu
mode=${1:-build}
out=${2:-}

pc="sdl2 cairo pangocairo"
deb="pkg-config libsdl2-dev libcairo2-dev libpango1.0-dev fonts-dejavu-core"
other="SDL2, cairo, Pango (with pangocairo), DejaVu fonts, pkg-config"
case $mode in
  test)  pc="$pc criterion"; deb="$deb libcriterion-dev xvfb xdotool x11-apps imagemagick"
         other="$other, Criterion, Xvfb, xdotool, ImageMagick" ;;
  bench) pc="$pc osmesa"; deb="$deb libosmesa6-dev"; other="$other, OSMesa (Mesa)" ;;
  grade) pc=; deb="bubblewrap"; other="bubblewrap (bwrap), the sandbox of make grade" ;;
  simde) pc=; deb="libsimde-dev"; other="SIMDe (SIMD Everywhere, header-only)" ;;
  aarch64) pc=; deb="gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user libsimde-dev"
         other="Debian's or Ubuntu's aarch64 cross compiler, qemu-user and SIMDe" ;;
esac

# SIMDe's headers where the compiler finds them
has_simde() {
  printf '#include <simde/x86/sse2.h>\n' | ${CC:-cc} -E -x c - >/dev/null 2>&1
}

missing() {
  case $mode in
    simde) has_simde || printf 'SIMDe '; return ;;
    grade) command -v bwrap >/dev/null 2>&1 || printf 'bwrap '; return ;;
    aarch64)
      command -v aarch64-linux-gnu-gcc >/dev/null 2>&1 || printf 'aarch64-linux-gnu-gcc '
      [ -f /usr/aarch64-linux-gnu/lib/libc.a ] || printf 'libc6-dev-arm64-cross '
      command -v qemu-aarch64 >/dev/null 2>&1 || printf 'qemu-aarch64 '
      [ -f /usr/include/simde/x86/sse2.h ] || printf 'SIMDe '
      return ;;
  esac
  command -v pkg-config >/dev/null 2>&1 || { echo pkg-config; return; }
  for p in $pc; do pkg-config --exists "$p" || printf '%s ' "$p"; done
  [ -f /usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf ] || printf 'fonts-dejavu '
  case $mode in test)
    command -v Xvfb >/dev/null 2>&1 || printf 'Xvfb '
    command -v xdotool >/dev/null 2>&1 || printf 'xdotool '
    command -v import >/dev/null 2>&1 || printf 'import(ImageMagick) ' ;;
  esac
}

need=$(missing)
if [ -n "$need" ]; then
  if [ -r /etc/debian_version ] && command -v apt-get >/dev/null 2>&1; then
    sudo=; [ "$(id -u)" -eq 0 ] || sudo=sudo
    echo "tristep: missing $need; installing Debian packages: $deb"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $deb >/dev/null
    need=$(missing)
    [ -z "$need" ] || { echo "tristep: still missing after apt-get: $need" >&2; exit 1; }
  else
    echo "tristep: missing $need. Please install: $other." >&2
    echo "  Debian/Ubuntu: apt-get install $deb" >&2
    case $mode in
      aarch64) echo "  (the aarch64 target uses Debian's cross packages; on an ARM64 machine, make test runs natively)" >&2 ;;
      grade) echo "  Fedora: dnf install bubblewrap; Arch: pacman -S bubblewrap" >&2
             echo "  (make grade's sandbox needs Linux's namespaces; where it cannot run, make grade UNSAFE=1" >&2
             echo "  grades without isolation, and its CSV says so)" >&2 ;;
      simde) echo "  Fedora: dnf install simde-devel" >&2
             echo "  macOS (Homebrew): brew install simde" >&2 ;;
      *) echo "  Fedora: dnf install pkgconf SDL2-devel cairo-devel pango-devel dejavu-sans-mono-fonts criterion-devel simde-devel xorg-x11-server-Xvfb xdotool ImageMagick mesa-libOSMesa-devel (Fedora 43 on: mesa-compat-libOSMesa-devel)" >&2
         echo "  macOS (Homebrew): brew install pkg-config sdl2 cairo pango criterion simde; brew install --cask font-dejavu (no OSMesa: make bench runs without the llvmpipe peer)" >&2 ;;
    esac
    exit 1
  fi
fi

if [ -n "$out" ] && [ -z "$pc" ]; then
  mkdir -p "$(dirname "$out")"
  echo "# written by src/deps.sh: $mode needs no system library beyond libc and libm" > "$out"
elif [ -n "$out" ]; then
  mkdir -p "$(dirname "$out")"
  {
    echo "# written by src/deps.sh: flags of the system libraries"
    echo "PKG_CFLAGS := $(pkg-config --cflags sdl2 cairo pangocairo)"
    echo "PKG_LIBS := $(pkg-config --libs sdl2 cairo pangocairo) -lm"
  } > "$out"
fi
