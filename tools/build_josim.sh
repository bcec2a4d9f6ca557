#!/usr/bin/env bash
# Build JoSIM (J. A. Delport et al., the superconducting circuit simulator,
# github.com/JoeyDelp/JoSIM) from its public source, for the benchmark
# data/bench/squid_josim_cost.py. JoSIM is a peer, not a dependency: nothing
# here is installed into pendula's venv and nothing is committed.
#
#   tools/build_josim.sh [BUILD_ROOT]        default BUILD_ROOT: /tmp/josim
#
# Sources: JoSIM and the three small CMake wrappers its build pulls in
# (CMakeSuiteSparse for KLU, CMakeSuperLU, CMakeCBLAS). If GIT_MIRROR is set,
# each is taken from $GIT_MIRROR/JoeyDelp+NAME/repo (a bare git directory);
# otherwise it is cloned from GitHub. The wrappers are handed to CMake's
# FetchContent as local source directories, so the build needs no network
# after the sources are in place. Needs cmake >= 3.14 and a C++17 compiler.
# The executable is BUILD_ROOT/build/josim-cli.
set -euo pipefail

ROOT=${1:-/tmp/josim}
SRC=$ROOT/src
BUILD=$ROOT/build
mkdir -p "$SRC" "$BUILD"

get_source() {  # NAME: put a work tree of JoeyDelp/NAME at $SRC/NAME
    local name=$1
    [ -d "$SRC/$name" ] && return 0
    if [ -n "${GIT_MIRROR:-}" ] && [ -d "$GIT_MIRROR/JoeyDelp+$name/repo" ]; then
        mkdir -p "$SRC/$name"
        git --git-dir="$GIT_MIRROR/JoeyDelp+$name/repo" archive HEAD | tar -x -C "$SRC/$name"
    else
        git clone --depth 1 "https://github.com/JoeyDelp/$name.git" "$SRC/$name"
    fi
}

for name in JoSIM CMakeSuiteSparse CMakeSuperLU CMakeCBLAS; do
    get_source "$name"
done

# JoSIM's CMakeLists asks git for its commit hash; without a .git it is empty (harmless)
cmake -S "$SRC/JoSIM" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release \
    -DFETCHCONTENT_FULLY_DISCONNECTED=ON \
    -DFETCHCONTENT_SOURCE_DIR_CMAKESUITESPARSE="$SRC/CMakeSuiteSparse" \
    -DFETCHCONTENT_SOURCE_DIR_CMAKESUPERLU="$SRC/CMakeSuperLU" \
    -DFETCHCONTENT_SOURCE_DIR_CMAKECBLAS="$SRC/CMakeCBLAS" \
    -DBUILD_TESTING=OFF
cmake --build "$BUILD" --target josim-cli -j "${JOBS:-1}"
echo "JoSIM built: $BUILD/josim-cli"
