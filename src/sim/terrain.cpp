#include "rownav/sim/terrain.hpp"
