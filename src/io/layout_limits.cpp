#include "layout_limits.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/statistics.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io::detail {
namespace {

/// Thrown by the parser callback; carries nothing: the position is found afterwards.
struct TooDeep {};

/// Byte offset of the bracket that first nests deeper than `max_depth` (strings skipped).
std::size_t too_deep_at(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return text.size();
}

}  // namespace

nlohmann::json parse_json_limited(const std::string& text, int max_depth, const std::string& file) {
  using nlohmann::json;
  // The callback sees the depth of the container being opened (0 = the document): stopping
  // there keeps every value shallow, so nothing later (dump, compare) recurses deeply.
  const json::parser_callback_t limit = [max_depth](int depth, json::parse_event_t event, json&) {
    if ((event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) &&
        depth >= max_depth)
      throw TooDeep{};
    return true;
  };
  try {
    return json::parse(text, limit);
  } catch (const json::parse_error& e) {
    throw InputError(file, "byte " + std::to_string(e.byte), "invalid JSON");
  } catch (const json::out_of_range&) {
    // A number too large for a double ("1E400") is not a parse_error in nlohmann::json 3.11.
    throw InputError(file, "", "invalid JSON: a number is out of range");
  } catch (const TooDeep&) {
    throw InputError(file, "byte " + std::to_string(too_deep_at(text, max_depth) + 1),
                     "layout.limits.max_json_depth: JSON nested deeper than " +
                         std::to_string(max_depth) + " levels");
  }
}

void check_layout_extent(const std::vector<LocatedPoint>& points, const sim::LayoutLimits& limits,
                         const std::string& file) {
  if (points.empty()) return;
  Eigen::Vector2d lo = points.front().p, hi = lo;
  for (const auto& q : points) lo = lo.cwiseMin(q.p), hi = hi.cwiseMax(q.p);
  const Eigen::Vector2d size = hi - lo;
  if (size.maxCoeff() <= limits.max_extent) return;
  std::vector<double> xs, ys;
  for (const auto& q : points) xs.push_back(q.p.x()), ys.push_back(q.p.y());
  const Eigen::Vector2d mid(core::median(xs), core::median(ys));
  const LocatedPoint* far = &points.front();
  for (const auto& q : points)
    if ((q.p - mid).cwiseAbs().maxCoeff() > (far->p - mid).cwiseAbs().maxCoeff()) far = &q;
  throw InputError(file, *far->where,
                   "layout.limits.max_extent: the layout spans " + core::detail::show(size.x()) +
                       " m x " + core::detail::show(size.y()) + " m, more than " +
                       core::detail::show(limits.max_extent) + " m; this point is " +
                       core::detail::show((far->p - mid).norm()) + " m from the median point");
}

}  // namespace rownav::io::detail
