# Shared by tools/test and tools/demo: where we are, how we report, and the one place that
# knows which Debian packages stereoscout needs. Sourced, not run.

STEREOSCOUT_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

# Everything a build, the tests and the benchmarks need, from Debian 12's own archive.
STEREOSCOUT_PACKAGES=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-features2d-dev libopencv-flann-dev
  libopencv-imgcodecs-dev
  libgpiod-dev
  libgtest-dev libbenchmark-dev
)

# The cross toolchain and the emulator for `tools/test --target aarch64`.
STEREOSCOUT_CROSS_PACKAGES=(g++-aarch64-linux-gnu qemu-user ca-certificates)

say() { printf '==> %s\n' "$*"; }
die() { printf '%s: error: %s\n' "${0##*/}" "$*" >&2; exit 1; }

# Runs a command as root: directly when we are root, else through sudo.
as_root() {
  if [ "$(id -u)" -eq 0 ]; then
    "$@"
  elif command -v sudo >/dev/null 2>&1; then
    sudo "$@"
  else
    die "need root to run '$*' (run as root, or install sudo)"
  fi
}

package_installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'
}

# Installs whatever of the given packages is missing; silent when nothing is.
install_missing_packages() {
  command -v dpkg-query >/dev/null 2>&1 || die "this is not a Debian system (no dpkg-query); install by hand: $*"
  local missing=()
  local package
  for package in "$@"; do
    package_installed "$package" || missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  say "installing missing Debian packages: ${missing[*]}"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get update -qq \
    || die "apt-get update failed (network or sources.list?)"
  if ! as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" \
      > /tmp/stereoscout-apt.log 2>&1; then
    for package in "${missing[@]}"; do
      apt-cache show "$package" >/dev/null 2>&1 \
        || die "Debian package '$package' is not available from the configured sources"
    done
    die "apt-get install failed for: ${missing[*]} (log: /tmp/stereoscout-apt.log)"
  fi
  for package in "${missing[@]}"; do
    package_installed "$package" || die "package '$package' did not install (log: /tmp/stereoscout-apt.log)"
  done
}

# Configures and builds one preset; dies naming the step that failed.
build_preset() {
  local preset=$1
  say "configure (preset $preset) -> build/$preset"
  cmake --preset "$preset" -S "$STEREOSCOUT_ROOT" > "/tmp/stereoscout-configure-$preset.log" 2>&1 \
    || { cat "/tmp/stereoscout-configure-$preset.log" >&2; die "cmake configure failed for preset '$preset'"; }
  say "build (preset $preset, $(nproc) jobs)"
  (cd "$STEREOSCOUT_ROOT" && cmake --build --preset "$preset" -j "$(nproc)") \
    || die "build failed for preset '$preset' (compiler output above)"
}
