#include "rownav/navigate/mission_plan.hpp"

#include <algorithm>
#include <string>

namespace rownav::navigate {

void MissionPlan::validate() const {
  for (std::size_t i = 0; i < corridors.size(); ++i) {
    const std::string name = "corridors[" + std::to_string(i) + "]";
    core::check_non_negative(corridors[i], name);
    if (i > 0) core::check(corridors[i] != corridors[i - 1], name, "repeats the previous corridor");
  }
  for (std::size_t i = 0; i < skip.size(); ++i)
    core::check_non_negative(skip[i], "skip[" + std::to_string(i) + "]");
  core::check_non_negative(stop_after, "stop_after");
  core::check_non_negative(block, "block");
  core::check_non_negative(start_corridor, "start_corridor");
}

std::vector<int> resolve_order(const MissionPlan& plan, int corridor_count) {
  plan.validate();
  std::vector<int> order;
  if (plan.corridors.empty()) {
    core::check(plan.start_corridor < corridor_count, "start_corridor",
                "corridor " + std::to_string(plan.start_corridor) + " does not exist (block has " +
                    std::to_string(corridor_count) + ")");
    for (int k = plan.start_corridor; k < corridor_count; ++k)
      if (std::find(plan.skip.begin(), plan.skip.end(), k) == plan.skip.end()) order.push_back(k);
  } else {
    for (std::size_t i = 0; i < plan.corridors.size(); ++i) {
      const int k = plan.corridors[i];
      core::check(k < corridor_count, "corridors[" + std::to_string(i) + "]",
                  "corridor " + std::to_string(k) + " does not exist (block has " +
                      std::to_string(corridor_count) + ")");
      if (std::find(plan.skip.begin(), plan.skip.end(), k) == plan.skip.end()) order.push_back(k);
    }
  }
  if (plan.stop_after > 0 && static_cast<int>(order.size()) > plan.stop_after)
    order.resize(static_cast<std::size_t>(plan.stop_after));
  core::check(!order.empty(), "corridors", "no corridor left to serve");
  return order;
}

std::vector<CorridorChange> corridor_changes(const std::vector<int>& order, TurnSide first_turn) {
  std::vector<CorridorChange> out;
  if (order.size() < 2) return out;
  // Index axis direction in the start heading's frame: +1 when indices grow to the left.
  const int first_dir = order[1] > order[0] ? 1 : -1;
  const int axis = side_sign(first_turn) * first_dir;
  for (std::size_t j = 0; j + 1 < order.size(); ++j) {
    CorridorChange c;
    c.from = order[j];
    c.to = order[j + 1];
    c.shift = std::abs(c.to - c.from);
    const int heading_parity = (j % 2 == 0) ? 1 : -1;  // the heading reverses in every corridor
    const int dir = c.to > c.from ? 1 : -1;
    c.side = axis * dir * heading_parity > 0 ? TurnSide::left : TurnSide::right;
    out.push_back(c);
  }
  return out;
}

}  // namespace rownav::navigate

namespace rownav::navigate {
std::vector<int> skip_order(int corridor_count, int min_shift) {
  std::vector<int> order;
  if (min_shift <= 1 || corridor_count < 2 * min_shift + 1) {
    for (int k = 0; k < corridor_count; ++k) order.push_back(k);
    return order;
  }
  for (int r = 0; r < min_shift; ++r)
    for (int k = r; k < corridor_count; k += min_shift) order.push_back(k);
  return order;
}
}  // namespace rownav::navigate
