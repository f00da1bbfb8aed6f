#include "drive.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include "rownav/io/progress.hpp"

namespace rownav::app {

namespace {

// Forwards to the user's sink while collecting the trajectory and lane statistics.
class Collector : public sim::SimSink {
 public:
  Collector(sim::SimSink& inner, DriveSummary& out) : inner_(inner), out_(out) {}
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>& l) override {
    ++out_.lidar_frames;
    inner_.on_cloud(c, l);
  }
  void on_scan(const core::Scan2D& s, const std::vector<sim::SurfaceClass>& l) override {
    ++out_.lidar_frames;
    inner_.on_scan(s, l);
  }
  void on_encoders(const core::WheelEncoderSample& s) override { inner_.on_encoders(s); }
  void on_imu(const core::ImuSample& s) override { inner_.on_imu(s); }
  void on_gnss(const core::GnssFix& s) override { inner_.on_gnss(s); }
  void on_ground_truth(const sim::GroundTruth& g) override {
    out_.trajectory.push_back(g.T_world_base.translation());
    if (g.place == sim::Place::lane) {
      sum_sq_ += g.lateral_error * g.lateral_error;
      ++lane_samples_;
      out_.lane_max_lateral = std::max(out_.lane_max_lateral, std::abs(g.lateral_error));
    }
    inner_.on_ground_truth(g);
  }
  double rms() const { return lane_samples_ ? std::sqrt(sum_sq_ / lane_samples_) : 0.0; }

 private:
  sim::SimSink& inner_;
  DriveSummary& out_;
  double sum_sq_ = 0.0;
  int lane_samples_ = 0;
};

}  // namespace

DriveSummary run_scripted_drive(sim::Simulator& sim, sim::PathFollower& driver,
                                sim::SimSink& sink, double max_time, bool progress) {
  DriveSummary out;
  Collector collector(sink, out);
  std::optional<io::Progress> bar;
  if (progress) bar.emplace("simulating", 100.0);
  const auto t0 = std::chrono::steady_clock::now();
  bool middle_taken = false;
  while (!driver.done() && sim.time() < max_time) {
    sim.step(driver.command(sim.robot_state().pose), collector);
    if (!middle_taken && driver.progress() >= 0.5 && sim.ground_truth().place == sim::Place::lane) {
      out.middle_truth = sim.ground_truth();
      middle_taken = true;
    }
    if (bar) bar->update(100.0 * driver.progress());
  }
  if (bar) bar->finish();
  out.completed = driver.done();
  out.sim_time = sim.time();
  out.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.plants_crushed = sim.ground_truth().plants_crushed;
  out.lane_rms_lateral = collector.rms();
  if (!middle_taken) out.middle_truth = sim.ground_truth();
  return out;
}

}  // namespace rownav::app
