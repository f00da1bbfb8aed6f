#pragma once
/// @file ros_cxx20_compat.hpp `Allocator::rebind<U>::other` for C++20.
///
/// ROS 1 message headers (gencpp) and ros/serialization.h spell container types as
/// `typename ContainerAllocator::template rebind<U>::other`, which C++20 removed from
/// std::allocator. The build mirrors the affected headers (ros/cmake/ros_cxx20_headers.cmake)
/// with `ContainerAllocator::` replaced by `::rownav_ros_compat::Rebind<ContainerAllocator>::`,
/// which is the upstream fix (ros/gencpp#51, ros/roscpp_core#124) expressed through
/// std::allocator_traits: same types, same ABI.
#include <memory>

namespace rownav_ros_compat {

/// Provides the pre-C++20 nested `rebind<U>::other` of allocator A.
template <class A>
struct Rebind {
  template <class U>
  struct rebind {
    using other = typename std::allocator_traits<A>::template rebind_alloc<U>;
  };
};

}  // namespace rownav_ros_compat
