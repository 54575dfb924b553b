#!/usr/bin/env bash
# Installs Intel Open Image Denoise 2.5.1 for `cargo build --features denoise`,
# from the PyPI wheel pyoidn 2.5.1.0 (the library with its CPU device; the
# wheel has no C headers, and the `oidn` crate needs none: it links the
# library and ships its own bindings).
#
#   bash scripts/setup-oidn.sh [DIR]          (DIR default: target/oidn)
#   bash scripts/setup-oidn.sh --all-devices [DIR]
#
# DIR gets lib/ with libOpenImageDenoise.so (-> .so.2 -> .so.2.5.1), its core
# library, the CPU device module and TBB; --all-devices adds the CUDA, HIP
# and SYCL device modules and their runtimes (about 180 MB instead of 56 MB).
# Running it again does nothing when DIR is complete. Needs python3 with pip
# (pip reaches PyPI). Ends by printing the environment to build and run with.
set -euo pipefail

VERSION=2.5.1
WHEEL=pyoidn-2.5.1.0-py3-none-manylinux2014_x86_64.whl
WHEEL_SHA256=32ad13368f8de1ef63001942ad05b02a00cd732d1206d97f352d3a3f606d823e

die() { echo "setup-oidn: $*" >&2; exit 1; }

all_devices=0
dir=""
for arg in "$@"; do
  case $arg in
    --all-devices) all_devices=1 ;;
    -h | --help) sed -n 2,14p "$0"; exit 0 ;;
    -*) die "unknown option $arg (try --help)" ;;
    *) [ -z "$dir" ] || die "one folder at most (got $dir and $arg)"; dir=$arg ;;
  esac
done

[ "$(uname -s)-$(uname -m)" = Linux-x86_64 ] ||
  die "the wheel is for Linux x86_64 only (this is $(uname -s) $(uname -m))"
command -v python3 >/dev/null || die "python3 is needed (to run pip and unpack the wheel)"

root=$(cd "$(dirname "$0")/.." && pwd)
dir=${dir:-$root/target/oidn}
mkdir -p "$dir" || die "cannot create $dir"
dir=$(cd "$dir" && pwd)
lib=$dir/lib

# The files kept from the wheel's pyoidn/oidn/lib/, and the links made to them.
files=(libOpenImageDenoise.so.$VERSION libOpenImageDenoise_core.so.$VERSION
  libOpenImageDenoise_device_cpu.so.$VERSION libtbb.so.12.19)
links=("libOpenImageDenoise.so.2 libOpenImageDenoise.so.$VERSION"
  "libOpenImageDenoise.so libOpenImageDenoise.so.2"
  "libtbb.so.12 libtbb.so.12.19" "libtbb.so libtbb.so.12")
if [ $all_devices = 1 ]; then
  files+=(libOpenImageDenoise_device_cuda.so.$VERSION libOpenImageDenoise_device_hip.so.$VERSION
    libOpenImageDenoise_device_sycl.so.$VERSION libsycl.so.9.0.0-0 libumf.so.1.1.0
    libur_loader.so.0.12.0 libur_adapter_level_zero.so.0.12.0 libur_adapter_level_zero_v2.so.0.12.0)
  links+=("libsycl.so.9 libsycl.so.9.0.0-0" "libumf.so.1 libumf.so.1.1.0"
    "libur_loader.so.0 libur_loader.so.0.12.0"
    "libur_adapter_level_zero.so.0 libur_adapter_level_zero.so.0.12.0"
    "libur_adapter_level_zero_v2.so.0 libur_adapter_level_zero_v2.so.0.12.0")
fi

complete() {
  local f l
  for f in "${files[@]}"; do [ -f "$lib/$f" ] || return 1; done
  for l in "${links[@]}"; do [ -e "$lib/${l%% *}" ] || return 1; done
}

if complete; then
  echo "setup-oidn: OIDN $VERSION already in $lib" >&2
else
  wheel=$dir/$WHEEL
  if [ -f "$wheel" ] && ! echo "$WHEEL_SHA256  $wheel" | sha256sum -c --status; then
    echo "setup-oidn: $wheel is damaged; downloading it again" >&2
    rm -f "$wheel"
  fi
  if [ ! -f "$wheel" ]; then
    echo "setup-oidn: downloading $WHEEL (88 MB) from PyPI" >&2
    python3 -m pip download "pyoidn==$VERSION.0" --no-deps --only-binary :all: -d "$dir" >&2 ||
      die "pip could not download pyoidn==$VERSION.0 (is PyPI reachable?)"
    [ -f "$wheel" ] || die "pip did not leave $WHEEL in $dir"
    echo "$WHEEL_SHA256  $wheel" | sha256sum -c --status ||
      die "$wheel does not have the expected SHA-256 $WHEEL_SHA256"
  fi
  # Unpack into a fresh folder and move it into place, so that an interrupted
  # run never leaves a half-written lib/.
  tmp=$(mktemp -d "$dir/.unpack.XXXXXX")
  trap 'rm -rf "$tmp"' EXIT
  python3 - "$wheel" "$tmp" "${files[@]}" <<'EOF' || die "could not unpack $wheel"
import os, sys, zipfile
wheel, out, names = sys.argv[1], sys.argv[2], sys.argv[3:]
with zipfile.ZipFile(wheel) as z:
    for name in names:
        with z.open("pyoidn/oidn/lib/" + name) as src, open(os.path.join(out, name), "wb") as dst:
            while chunk := src.read(1 << 20):
                dst.write(chunk)
        os.chmod(os.path.join(out, name), 0o755)
EOF
  for l in "${links[@]}"; do ln -sfn "${l#* }" "$tmp/${l%% *}"; done
  chmod 755 "$tmp"
  rm -rf "$lib"
  mv "$tmp" "$lib"
  trap - EXIT
  complete || die "internal error: $lib is incomplete after unpacking"
  echo "setup-oidn: OIDN $VERSION installed in $lib" >&2
fi

# What to build and run with (stdout, so that `eval "$(bash scripts/setup-oidn.sh)"` works).
echo "export OIDN_DIR=$dir"
echo "export LD_LIBRARY_PATH=$lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
