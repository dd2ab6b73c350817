#!/usr/bin/env bash
# Installs the Debian packages proxima builds with, only those that are missing.
# Idempotent; works as root, or through sudo when not root and sudo is available.
# --fuzz also installs clang with its sanitizer and libFuzzer runtimes (scripts/fuzz.sh,
# CI); `make test` and `make demo` do not need them. --browser also installs Chromium, for
# scripts/screenshot-report.sh (headless check + screenshot of the demo report).
# --real-content also installs the real-content corpus' packages (scripts/real-content.sh).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libglm-dev libembree-dev libtbb-dev libassimp-dev
  libstb-dev libtinyexr-dev libturbojpeg0-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # Optional llvmpipe harness of `proxima bench raster` (bench/llvmpipe): Mesa's
  # software OpenGL through EGL, measured side by side with proxima's rasterizer.
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  # `proxima view` (issue 12): the SDL2 window (optional at build time: without it the
  # viewer exits 2), and Xvfb + xauth so its screenshot tests run without a display.
  libsdl2-dev xvfb xauth
  # The Python module (cmake/python.cmake, docs/python.md) and its pytest suite, for
  # Debian's /usr/bin/python3; matplotlib for examples/python.
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib
)
for arg in "$@"; do
  case "$arg" in
    --fuzz) packages+=(clang libclang-rt-dev zlib1g-dev) ;;
    --browser) packages+=(chromium) ;;
    # scripts/real-content.sh: the packages that ship the corpus' models, and the tools that
    # unpack and convert them. (blender-data's HDR environments are latitude-longitude maps;
    # scene files take six cube faces, so they are not installed.)
    --real-content) packages+=(assimp-utils assimp-testmodels sweethome3d-furniture glmark2-data libcgal-demo unzip) ;;
    *) echo "install-deps: unknown option $arg (--fuzz, --browser, --real-content)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "install-deps: missing packages (${missing[*]}) and not root; install them or run as root" >&2
  exit 2
fi

echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
