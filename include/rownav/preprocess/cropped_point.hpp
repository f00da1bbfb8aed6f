#pragma once
/// @file cropped_point.hpp A point kept by the crop, as the later 3D passes read it: its
/// coordinates and its index in the frame (16 bytes instead of the frame's 24), so that the
/// ground estimate and the height band read a compact array and the voxel grid fetches the other
/// fields (intensity, time, ring, column) only for the points it keeps.
#include <cstdint>

namespace rownav::preprocess {

/// Coordinates of a cropped point and where it is in the input cloud.
struct CroppedPoint {
  float x = 0.0f;           ///< [m] base frame
  float y = 0.0f;           ///< [m] base frame
  float z = 0.0f;           ///< [m] base frame
  std::uint32_t index = 0;  ///< position of the point in the cloud given to the crop
};

}  // namespace rownav::preprocess
