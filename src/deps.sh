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
# With OUT, writes the compiler and linker flags as a makefile fragment.
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
esac

missing() {
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
    echo "  Fedora: dnf install pkgconf SDL2-devel cairo-devel pango-devel dejavu-sans-mono-fonts criterion-devel mesa-libOSMesa-devel xorg-x11-server-Xvfb xdotool ImageMagick" >&2
    echo "  macOS (Homebrew): brew install pkg-config sdl2 cairo pango criterion font-dejavu" >&2
    exit 1
  fi
fi

if [ -n "$out" ]; then
  mkdir -p "$(dirname "$out")"
  {
    echo "# written by src/deps.sh: flags of the system libraries"
    echo "PKG_CFLAGS := $(pkg-config --cflags sdl2 cairo pangocairo)"
    echo "PKG_LIBS := $(pkg-config --libs sdl2 cairo pangocairo) -lm"
  } > "$out"
fi
