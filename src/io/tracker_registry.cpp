#include "rownav/io/tracker_registry.hpp"

#include <yaml-cpp/yaml.h>

#include <functional>
#include <string_view>

#include "rownav/io/section_registry.hpp"
#include "rownav/track/line_ekf.hpp"
#include "rownav/track/model_filter.hpp"
#include "rownav/track/raw_corridor.hpp"
#include "rownav/track/model_matching.hpp"

namespace rownav::io {

namespace {

using Registry = SectionRegistry<track::RowTracker>;

// Registered trackers: adding one is one line here (and its section in config/track/*.yaml).
const Registry& registry() {
  static const Registry r(
      "--tracker", "tracker",
      {
          {"model_matching",
           Registry::creator<track::ModelMatchingTracker, track::ModelMatchingConfig>()},
          {"line_ekf", Registry::creator<track::LineEkfTracker, track::LineEkfConfig>()},
          {"model_filter", Registry::creator<track::ModelFilterTracker, track::ModelFilterConfig>()},
          {"none", Registry::creator<track::RawCorridorTracker, track::RawCorridorConfig>()},
      });
  return r;
}

}  // namespace

std::vector<std::string> tracker_names() { return registry().names(); }

std::unique_ptr<track::RowTracker> make_tracker(const std::string& name,
                                                const std::filesystem::path& config) {
  return registry().make(name, config);
}

}  // namespace rownav::io
