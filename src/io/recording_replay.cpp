// A recording played into NavStack in arrival order (io/recording_replay.hpp).
#include "rownav/io/recording_replay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rownav/io/csv.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace fs = std::filesystem;

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

/// The recorded streams, each consumed in stamp order up to a time.
class Streams {
 public:
  /// `truth`: the ground-truth poses as the external odometry instead of the encoders and
  /// GNSS; else the recording's own external odometry (a bag's), if it has one.
  Streams(const Recording& rec, navigate::NavStack& stack, bool truth)
      : rec_(rec), stack_(stack), truth_(truth) {
    if (!truth) return;
    truth_poses_.reserve(rec.ground_truth.size());
    for (const auto& g : rec.ground_truth) truth_poses_.push_back({g.stamp, g.T_world_base, g.twist});
  }

  /// Feeds every sample stamped at or before t.
  void feed_until(double t) {
    while (true) {
      const double te = truth_ || ie_ >= rec_.encoders.size() ? kNever : rec_.encoders[ie_].stamp;
      const double ti = ii_ < rec_.imu.size() ? rec_.imu[ii_].stamp : kNever;
      const double tg = truth_ || ig_ >= rec_.gnss.size() ? kNever : rec_.gnss[ig_].stamp;
      const double tt = it_ < poses().size() ? poses()[it_].stamp : kNever;
      const double next = std::min({te, ti, tg, tt});
      if (!(next <= t)) return;
      if (te == next)
        stack_.on_encoders(rec_.encoders[ie_++]);
      else if (ti == next)
        stack_.on_imu(rec_.imu[ii_++]);
      else if (tg == next)
        stack_.on_gnss(rec_.gnss[ig_++]);
      else
        stack_.on_odometry(poses()[it_++]);
    }
  }

 private:
  const std::vector<localize::StampedPose>& poses() const {
    return truth_ ? truth_poses_ : rec_.odometry;
  }

  const Recording& rec_;
  navigate::NavStack& stack_;
  bool truth_;
  std::vector<localize::StampedPose> truth_poses_;
  std::size_t ie_ = 0, ii_ = 0, ig_ = 0, it_ = 0;
};

}  // namespace

double sweep_period(const Recording& rec, double fallback) {
  std::vector<double> d;
  for (std::size_t i = 1; i < rec.cloud_stamps.size(); ++i)
    d.push_back(rec.cloud_stamps[i] - rec.cloud_stamps[i - 1]);
  for (std::size_t i = 1; i < rec.scans.size(); ++i)
    d.push_back(rec.scans[i].stamp - rec.scans[i - 1].stamp);
  if (d.empty()) return fallback;
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  const double p = d[d.size() / 2];
  return p > 0.0 && std::isfinite(p) ? p : fallback;
}

void replay_recording(const Recording& rec, navigate::NavStack& stack, const ReplayOptions& options,
                      const std::function<void(const navigate::NavCommand&)>& on_frame) {
  const double period = sweep_period(rec, stack.config().stack.sweep_period);
  Streams streams(rec, stack, options.truth_odometry);
  std::size_t ic = 0, is = 0;
  while (ic < rec.cloud_count() || is < rec.scans.size()) {
    const double tc = ic < rec.cloud_count() ? rec.cloud_stamps[ic] : kNever;
    const double ts = is < rec.scans.size() ? rec.scans[is].stamp : kNever;
    const double arrival = std::min(tc, ts) + period;  // the sweep is complete then
    streams.feed_until(arrival);
    if (tc <= ts)
      stack.on_cloud(rec.cloud(ic++));
    else
      stack.on_scan(rec.scans[is++]);
    const navigate::NavCommand c = stack.command(arrival);
    if (c.frame) on_frame(c);
  }
}

namespace {

template <class V>
const auto& at(const V& v, std::int64_t i, const CsvReader& r, const fs::path& file) {
  if (i < 0 || static_cast<std::size_t>(i) >= v.size())
    throw InputError(file.string(), std::to_string(r.line()),
                     "index " + std::to_string(i) + " outside its stream");
  return v[static_cast<std::size_t>(i)];
}

/// The samples as they are.
class StackSink : public InputLogSink {
 public:
  explicit StackSink(navigate::NavStack& stack) : stack_(stack) {}
  void on_encoders(const core::WheelEncoderSample& s) override { stack_.on_encoders(s); }
  void on_imu(const core::ImuSample& s) override { stack_.on_imu(s); }
  void on_gnss(const core::GnssFix& s) override { stack_.on_gnss(s); }
  void on_cloud(core::PointCloud cloud) override { stack_.on_cloud(std::move(cloud)); }
  void on_scan(core::Scan2D scan) override { stack_.on_scan(std::move(scan)); }
  navigate::NavCommand command(double stamp) override { return stack_.command(stamp); }

 private:
  navigate::NavStack& stack_;
};

}  // namespace

std::vector<ReplayedCommand> replay_input_log(const Recording& rec, navigate::NavStack& stack) {
  StackSink sink(stack);
  return replay_input_log(rec, sink);
}

std::vector<ReplayedCommand> replay_input_log(const Recording& rec, InputLogSink& stack) {
  const fs::path file = rec.dir / kInputLog;
  CsvReader r(file);
  std::vector<ReplayedCommand> out;
  r.next();  // header
  while (r.next()) {
    r.expect_size(6);
    const std::string_view kind = r.cell(0);
    const std::int64_t i = r.integer(1, "index");
    if (kind == "encoders") {
      stack.on_encoders(at(rec.encoders, i, r, file));
    } else if (kind == "imu") {
      stack.on_imu(at(rec.imu, i, r, file));
    } else if (kind == "gnss") {
      stack.on_gnss(at(rec.gnss, i, r, file));
    } else if (kind == "scan") {
      stack.on_scan(at(rec.scans, i, r, file));
    } else if (kind == "cloud") {
      at(rec.cloud_stamps, i, r, file);
      stack.on_cloud(rec.cloud(static_cast<std::size_t>(i)));
    } else if (kind == "command") {
      ReplayedCommand c;
      c.stamp = r.number(2, "stamp");
      c.live = {r.number(3, "v"), 0.0, r.number(4, "omega")};
      c.live_state = std::string(r.cell(5));
      const navigate::NavCommand n = stack.command(c.stamp);
      c.replayed = n.cmd;
      c.replayed_state = std::string(core::enum_name(n.state));
      out.push_back(std::move(c));
    } else {
      throw InputError(file.string(), std::to_string(r.line()),
                       "unknown input kind '" + std::string(kind) + "'");
    }
  }
  return out;
}

}  // namespace rownav::io
