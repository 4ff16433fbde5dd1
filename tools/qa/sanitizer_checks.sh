#!/bin/sh
# The CI's sanitizer steps (docs/testing.md, "Sanitizers and fuzzing"). Run from the repository:
#   sh tools/qa/sanitizer_checks.sh [build folder prefix, default build-]
# 1. AddressSanitizer + UndefinedBehaviorSanitizer (Clang, -O1): the tests labelled "asan" run,
#    then each fuzz target for ISODEL_FUZZ_SECONDS from its seeds (label "fuzz").
# 2. ThreadSanitizer: the tests labelled "tsan" (the parallel stages, at 1 and 2 threads).
# Each build is a unity build of only the targets its tests need: no benchmarks, no Python module,
# no test file it does not run (ISODEL_TEST_SUBSET, tests/CMakeLists.txt). Needs clang,
# libclang-rt-14-dev and dpkg-dev (the README's install line). The run options (halt on the
# first report, suppressions) are CTest's ISODEL_SANITIZER_ENV, set in cmake/Sanitize.cmake.
set -e
prefix=${1:-build-}
jobs=$(nproc)
here=$(pwd)
# MPI off: the sanitized command line is never run under mpirun (the release build's
# cli/test_partitioned_mpi_cli is), and Open MPI's own allocations are not ours to sanitize.
common="-G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON
        -DISODEL_BUILD_PYTHON=OFF -DISODEL_BUILD_BENCHMARKS=OFF -DISODEL_WITH_MPI=OFF"

# 1. ASan + UBSan, and the fuzz smoke runs.
cmake -S . -B "${prefix}asan" $common "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" \
      -DISODEL_SANITIZE=address,undefined -DISODEL_FUZZ=ON -DISODEL_TEST_SUBSET=asan
cmake --build "${prefix}asan" --target fuzz_targets make_fuzz_seeds isodel_cli sanitizer_canary \
      test_io test_octree test_geometry test_delaunay test_closed_ball test_verify test_cli
ctest --test-dir "${prefix}asan" -L "asan|fuzz" --output-on-failure -j "$jobs"

# 2. TSan sees only the synchronisation of instrumented code, and Debian's libtbb is not: the
# scheduler's hand-offs would all look like races. So the same oneTBB release is built with TSan
# from Debian's source package, fetched through a private apt list (the system's is untouched).
# Its headers are the installed ones (same release), so the build compiles as usual; at run time
# LD_LIBRARY_PATH puts the instrumented libtbb in front of the system's, for OpenVDB too.
case "$prefix" in
  /*) tbb="${prefix}tsan-tbb" ;;
  *) tbb="$here/${prefix}tsan-tbb" ;;
esac
if [ ! -f "$tbb/install/lib/libtbb.so.12" ]; then
  rm -rf "$tbb" && mkdir -p "$tbb/apt/lists/partial" "$tbb/src"
  codename=$(. /etc/os-release && echo "$VERSION_CODENAME")
  for suite in "$codename" "$codename-updates"; do
    echo "deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian $suite main"
  done > "$tbb/apt/sources.list"
  apt_private="-o Dir::Etc::SourceList=$tbb/apt/sources.list -o Dir::Etc::SourceParts=/nonexistent -o Dir::State::Lists=$tbb/apt/lists"
  apt-get $apt_private update
  (cd "$tbb/src" && apt-get $apt_private source "$(dpkg-query -W -f '${source:Package}=${source:Version}' libtbb-dev)")
  cmake -S "$(ls -d "$tbb"/src/onetbb-*/ | head -1)" -B "$tbb/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DTBB_SANITIZE=thread -DTBB_TEST=OFF \
        -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF -DCMAKE_INSTALL_PREFIX="$tbb/install"
  cmake --build "$tbb/build" && cmake --install "$tbb/build"
fi
cmake -S . -B "${prefix}tsan" $common "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" -DISODEL_SANITIZE=thread -DISODEL_TEST_SUBSET=tsan
cmake --build "${prefix}tsan" --target isodel_cli sanitizer_canary test_surface test_octree test_delaunay
export LD_LIBRARY_PATH="$tbb/install/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if ! ldd "${prefix}tsan/bin/test_octree" | grep -q "$tbb/install/lib/libtbb.so.12"; then
  echo "sanitizer_checks: the TSan tests do not load the instrumented libtbb" >&2
  exit 1
fi
ctest --test-dir "${prefix}tsan" -L tsan --output-on-failure -j "$jobs"
