/// @file place.cpp Allowed place transitions (Emmi 2021 Fig. 1b).
#include "rownav/map/place.hpp"

namespace rownav::map {

bool transition_allowed(Place from, Place to) {
  if (from == to || from == Place::unknown || to == Place::unknown) return true;
  // Emmi 2021 Fig. 1b: every transition goes through the headland.
  return from == Place::headland || to == Place::headland;
}

}  // namespace rownav::map
