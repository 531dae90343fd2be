#!/bin/sh
# Install the Debian packages this project needs (as root). With --print, only print the command.
# Quiet and quick when everything is already there.
set -eu
PKGS="petsc-dev libopenblas0-pthread gmsh libgmsh-dev python3 python3-matplotlib python3-h5py python3-numpy make gcc openmpi-bin valgrind clang-format"
missing=""
for p in $PKGS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
line="apt-get update && apt-get install -y$missing"
if [ "${1:-}" = "--print" ] || [ "$(id -u)" != 0 ]; then
  echo "Missing Debian packages:$missing"
  echo "Install them as root with:"
  echo "  $line"
  exit 1
fi
echo "Installing:$missing"
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q $missing
