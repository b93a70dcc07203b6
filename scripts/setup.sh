#!/usr/bin/env bash
# wardmap set-up on Debian 12: installs every package the project needs, builds Release into
# build/, and (unless --no-run) runs the main job on the default input.
#   scripts/setup.sh            install + build + run the default job
#   scripts/setup.sh --no-run   install + build only
#   scripts/setup.sh --deps-only install the packages only (what scripts/test.sh uses)
#   scripts/setup.sh --deps-only --with-clang   also clang and its runtimes (what scripts/fuzz.sh uses)
#   scripts/setup.sh --deps-only --with-lint    also cppcheck and clang-tidy (what scripts/lint.sh uses)
# Idempotent; works as root or through sudo.
set -euo pipefail
cd "$(dirname "$0")/.."
RUN_MAIN=1
DEPS_ONLY=0
WITH_CLANG=0
WITH_LINT=0
for a in "$@"; do
  case "$a" in
    --no-run) RUN_MAIN=0 ;;
    --deps-only) DEPS_ONLY=1 ;;
    --with-clang) WITH_CLANG=1 ;;
    --with-lint) WITH_LINT=1 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown option '$a' (see --help)" >&2; exit 2 ;;
  esac
done

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup.sh: not root and no sudo: run as root" >&2; exit 2; }
  SUDO="sudo"
fi

PKGS=(build-essential cmake pkg-config git ca-certificates
      libopencv-dev libeigen3-dev libceres-dev colmap libtinygltf-dev libvtk9-dev
      libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev libspdlog-dev
      libyaml-cpp-dev xvfb xauth)
# Node runs the Khronos glTF validator in the tests. Ask apt for Debian's nodejs and npm only when
# there is no npm at all: a NodeSource nodejs bundles npm and conflicts with Debian's npm package.
command -v npm >/dev/null || PKGS+=(nodejs npm)
# libFuzzer and the sanitizer runtimes of clang 14, Debian 12's clang.
[ $WITH_CLANG -eq 0 ] || PKGS+=(clang libclang-rt-14-dev)
# Static analysis (scripts/lint.sh).
[ $WITH_LINT -eq 0 ] || PKGS+=(cppcheck clang-tidy)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup.sh: installing ${#missing[@]} Debian packages: ${missing[*]}"
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get update
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "setup.sh: all Debian packages present"
fi

# The glTF validator (npm package gltf-validator, tests/tools/package.json), installed as the
# invoking user into tests/tools/node_modules. Optional: without it the validator test skips and says
# so (e.g. behind a proxy npm does not trust).
if [ -d tests/tools/node_modules/gltf-validator ]; then
  echo "setup.sh: glTF validator present"
else
  echo "setup.sh: installing the glTF validator (npm) into tests/tools"
  npm install --prefix tests/tools --no-audit --no-fund ||
    echo "setup.sh: warning: 'npm install --prefix tests/tools' failed (is the npm registry reachable?);" \
      "the glTF validator test will be skipped" >&2
fi

[ "$DEPS_ONLY" -eq 1 ] && exit 0

JOBS=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$JOBS"

if [ "$RUN_MAIN" -eq 1 ]; then
  echo "setup.sh: running the main job on the default input"
  scripts/run-default.sh
fi
