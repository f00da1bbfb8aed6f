# Mirrors ROS 1 headers that use `ContainerAllocator::template rebind<U>::other` (removed from
# std::allocator in C++20) into a build directory, patched to go through
# rownav_ros_compat::Rebind (ros/compat/rownav_ros/ros_cxx20_compat.hpp). Unpatched siblings are
# symlinked so that quoted includes next to a patched header still resolve. The mirror is put
# before the system include directory of the ROS targets.
#
# rownav_ros_mirror_headers(<out_dir> <include_root> <package dir>...)
function(rownav_ros_mirror_headers out_dir root)
  set(_patched 0)
  foreach(_pkg ${ARGN})
    if(NOT IS_DIRECTORY "${root}/${_pkg}")
      continue()
    endif()
    file(GLOB_RECURSE _headers RELATIVE "${root}" "${root}/${_pkg}/*.h" "${root}/${_pkg}/*.hpp")
    foreach(_h ${_headers})
      set(_dst "${out_dir}/${_h}")
      file(READ "${root}/${_h}" _text)
      string(FIND "${_text}" "ContainerAllocator::template rebind<" _at)
      if(_at EQUAL -1)
        if(NOT EXISTS "${_dst}")
          get_filename_component(_dir "${_dst}" DIRECTORY)
          file(MAKE_DIRECTORY "${_dir}")
          file(CREATE_LINK "${root}/${_h}" "${_dst}" SYMBOLIC)
        endif()
        continue()
      endif()
      string(REPLACE "typename ContainerAllocator::template rebind<"
                     "typename ::rownav_ros_compat::Rebind<ContainerAllocator>::template rebind<"
                     _text "${_text}")
      set(_text "#include <rownav_ros/ros_cxx20_compat.hpp>  // rownav: C++20 rebind\n${_text}")
      if(IS_SYMLINK "${_dst}")
        file(REMOVE "${_dst}")  # never write through a symlink into the system headers
      endif()
      get_filename_component(_dir "${_dst}" DIRECTORY)
      file(MAKE_DIRECTORY "${_dir}")
      file(WRITE "${_dst}.tmp" "${_text}")
      file(COPY_FILE "${_dst}.tmp" "${_dst}" ONLY_IF_DIFFERENT)  # no rebuild on re-configure
      file(REMOVE "${_dst}.tmp")
      math(EXPR _patched "${_patched} + 1")
    endforeach()
  endforeach()
  message(STATUS "rownav: ROS headers patched for C++20: ${_patched} (mirror ${out_dir})")
endfunction()
