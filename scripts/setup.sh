#!/usr/bin/env bash
# Installs the Debian packages reftrack needs to build, test and run its demo.
# Idempotent and non-interactive; works as root or through sudo.
# --fuzz: also what scripts/fuzz.sh needs (clang's libFuzzer and sanitizer runtimes); the build
# itself never needs them.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git
  libopencv-dev libopencv-contrib-dev   # OpenCV 4.6 with contrib (aruco)
  libeigen3-dev libceres-dev            # math, least squares
  libglfw3-dev libglm-dev               # window, GL math
  libimgui-dev libstb-dev               # Dear ImGui 1.86 (+ its stb dependency)
  libosmesa6-dev libegl-dev             # off-screen GL (OSMesa; EGL surfaceless kept possible)
  python3-glad                          # GL loader generator (build time)
  libtinyobjloader-dev libcli11-dev libgtest-dev
  libyaml-cpp-dev                       # YAML 1.2 parser for user-written files (yaml-cpp 0.7)
  pybind11-dev python3-dev python3-numpy python3-opencv  # the Python module `reftrack`
  xvfb xauth                            # window tests on a headless machine
  ffmpeg                                # ffprobe checks recorded MP4s; video codecs
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev  # the recorder's fragmented MP4
  ccache                                # faster rebuilds
)
if [ "${1:-}" = "--fuzz" ]; then
  PACKAGES+=(clang libclang-rt-14-dev libfuzzer-14-dev)  # scripts/fuzz.sh only
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} Debian packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "setup: need root or sudo to install: ${missing[*]}" >&2
    exit 1
  fi
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
