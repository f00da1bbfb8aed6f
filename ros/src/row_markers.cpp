// Tracked rows and corridor as RViz markers (rownav_ros/row_markers.hpp).
#include "rownav_ros/row_markers.hpp"

#include <cmath>

namespace rownav::ros_bridge {

namespace {

using visualization_msgs::Marker;

Marker line(const std::string& frame, const ros::Time& stamp, const std::string& ns, int id,
            const RowMarkerStyle& style) {
  Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = Marker::LINE_STRIP;
  m.action = Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = style.line_width;
  m.color.a = 1.0;
  m.lifetime = ros::Duration(style.lifetime);
  return m;
}

void add_point(Marker& m, const core::Line2& l, double x) {
  // The line's point at abscissa x (lines are oriented towards +x: direction.x() > 0).
  const double t = std::abs(l.direction.x()) > 1e-9 ? (x - l.point.x()) / l.direction.x() : 0.0;
  geometry_msgs::Point p;
  p.x = l.point.x() + t * l.direction.x();
  p.y = l.point.y() + t * l.direction.y();
  m.points.push_back(p);
}

}  // namespace

visualization_msgs::MarkerArray row_markers(const track::RowTracking& tracking,
                                            const std::string& frame, const ros::Time& stamp,
                                            const RowMarkerStyle& style) {
  visualization_msgs::MarkerArray a;
  Marker clear;
  clear.header.frame_id = frame;
  clear.header.stamp = stamp;
  clear.action = Marker::DELETEALL;
  a.markers.push_back(clear);
  for (std::size_t i = 0; i < tracking.rows.size(); ++i) {
    const auto& r = tracking.rows[i];
    if (!(r.x_max > r.x_min)) continue;
    Marker m = line(frame, stamp, "rows", static_cast<int>(i), style);
    const bool followed = static_cast<int>(i) == tracking.left || static_cast<int>(i) == tracking.right;
    m.color.r = followed ? 0.1f : 0.6f;
    m.color.g = followed ? 0.8f : 0.6f;
    m.color.b = followed ? 0.2f : 0.6f;
    add_point(m, r.line_base, r.x_min);
    add_point(m, r.line_base, r.x_max);
    a.markers.push_back(m);
  }
  if (tracking.status != track::TrackStatus::lost) {
    Marker c = line(frame, stamp, "corridor", 0, style);
    c.color.r = 0.2f, c.color.g = 0.4f, c.color.b = 1.0f;
    add_point(c, tracking.centre_line_base, 0.0);
    add_point(c, tracking.centre_line_base, style.corridor_ahead);
    a.markers.push_back(c);
  }
  return a;
}

}  // namespace rownav::ros_bridge
