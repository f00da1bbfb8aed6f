# Precompiled headers (ROWNAV_PCH, on by default): the standard library and Eigen headers that
# almost every translation unit includes, parsed once per target instead of once per file.
# Measured on 2 cores (BENCHMARK.md, "build time and the fuzz runs in make test"): the clean
# Release build 18.2 -> 16.5 min (most of a file's 5-20 s is -O3 code generation, not parsing
# these headers). Only external headers are listed, so editing a rownav header rebuilds what
# includes it, not the whole target; every file still includes what it uses (the build with
# -DROWNAV_PCH=OFF is the check).
option(ROWNAV_PCH "Precompile the standard and Eigen headers of each target (build time)" ON)

set(ROWNAV_PCH_HEADERS
    <algorithm> <array> <cmath> <cstdint> <deque> <filesystem> <fstream> <functional> <limits>
    <map> <memory> <optional> <random> <span> <sstream> <stdexcept> <string> <string_view>
    <utility> <vector> <Eigen/Dense>)

# rownav_precompile(<target> [<header>...]): the common set plus the target's own headers
# (e.g. <gtest/gtest.h> for a test executable). No-op with ROWNAV_PCH=OFF.
function(rownav_precompile target)
  if(ROWNAV_PCH)
    target_precompile_headers(${target} PRIVATE ${ROWNAV_PCH_HEADERS} ${ARGN})
  endif()
endfunction()
