# The core's one-way data flow, checked on the sources (ctest: layering.core_stages):
# sensor samples -> localize -> preprocess -> detect -> track -> map -> control -> navigate.
# A core stage includes only rownav/core and the stages before it in that list; no core stage
# includes an adapter (sim, io, vision, eval, render). The CMake targets cannot catch a
# header-only include between stages of the one rownav_core library; this does.
# Usage: cmake -DROOT=<source dir> -P scripts/check_layering.cmake
if(NOT ROOT)
  message(FATAL_ERROR "check_layering: -DROOT=<source dir> required")
endif()
set(_order core localize preprocess detect track map control navigate)
set(_violations "")
set(_allowed core)
foreach(stage IN LISTS _order)
  file(GLOB_RECURSE _files ${ROOT}/include/rownav/${stage}/*.hpp ${ROOT}/src/${stage}/*.cpp)
  foreach(f IN LISTS _files)
    file(STRINGS ${f} _includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"rownav/[a-z_0-9]+/")
    foreach(line IN LISTS _includes)
      string(REGEX REPLACE "^[^\"]*\"rownav/([a-z_0-9]+)/.*$" "\\1" _dep "${line}")
      if(NOT _dep STREQUAL stage)
        list(FIND _allowed ${_dep} _i)
        if(_i EQUAL -1)
          file(RELATIVE_PATH _rel ${ROOT} ${f})
          string(APPEND _violations "  ${_rel}: ${stage} includes rownav/${_dep}/\n")
        endif()
      endif()
    endforeach()
  endforeach()
  list(APPEND _allowed ${stage})
endforeach()
if(_violations)
  message(FATAL_ERROR "check_layering: includes against the data flow "
                      "(${_order}):\n${_violations}")
endif()
message(STATUS "check_layering: every core stage includes only the stages before it")
