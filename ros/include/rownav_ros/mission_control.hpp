#pragma once
/// @file mission_control.hpp Start / pause / stop of a mission by an operator (rownav_node's
/// ~start, ~pause, ~stop services): the phase, the one-line answers, the command gate and the
/// state to publish. No ROS in it.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/navigate/navigator.hpp"

namespace rownav::ros_bridge {

/// Where the operator has put the mission.
enum class MissionPhase : std::uint8_t {
  waiting,  ///< not started yet (NodeConfig::autostart false): command zero until start
  running,  ///< the navigator's command is sent
  paused,   ///< command zero; start resumes where the mission was
  stopped,  ///< command zero: the mission is over (start begins a new one from where it stands)
};

/// The answer to an operator's request (std_srvs/Trigger's success and message).
struct MissionAnswer {
  bool success = false;
  std::string message;  ///< one line: what happened
  /// the caller begins a new mission from where the robot stands (NavStack::restart_mission)
  bool new_mission = false;
};

/// The operator's mission phase. After a stop, or once the navigator ended the mission (done,
/// safe_stop), start begins a new mission (MissionAnswer::new_mission) instead of resuming.
/// Pure state, no clock: the caller applies gate() to every command.
class MissionControl {
 public:
  /// `autostart`: running from the start (true) or waiting for start().
  explicit MissionControl(bool autostart);

  /// Begins the mission (waiting), resumes it (paused), or begins a new one (new_mission) once
  /// stopped or when the navigator ended it (`nav` done / safe_stop).
  MissionAnswer start(navigate::NavState nav);
  /// Command zero at once, the mission kept; refused once stopped. `nav` words the answer (a
  /// pause in an odometry-closed manoeuvre counts into its time budget).
  MissionAnswer pause(navigate::NavState nav);
  /// Whether start(nav) would begin a new mission (after a stop, done or safe_stop).
  bool starts_new_mission(navigate::NavState nav) const;
  /// Command zero until a new mission is started. Always succeeds.
  MissionAnswer stop(navigate::NavState nav);

  MissionPhase phase() const { return phase_; }
  bool running() const { return phase_ == MissionPhase::running; }
  /// The command to send: `cmd` while running, exactly zero otherwise.
  core::Twist2 gate(const core::Twist2& cmd) const { return running() ? cmd : core::Twist2{}; }
  /// The state to publish: the navigator's while running or once it ended the mission
  /// (done / safe_stop), else the phase (waiting, paused, stopped).
  std::string state(navigate::NavState nav) const;

 private:
  MissionPhase phase_;
};

/// Whether the navigator has ended the mission (done or safe_stop).
bool mission_ended(navigate::NavState nav);

}  // namespace rownav::ros_bridge

template <>
struct rownav::core::EnumNames<rownav::ros_bridge::MissionPhase> {
  using E = rownav::ros_bridge::MissionPhase;
  static constexpr std::array<std::pair<E, std::string_view>, 4> values{{{E::waiting, "waiting"},
                                                                         {E::running, "running"},
                                                                         {E::paused, "paused"},
                                                                         {E::stopped, "stopped"}}};
};
