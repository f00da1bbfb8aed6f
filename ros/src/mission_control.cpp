// Start / pause / stop of a mission by an operator.
#include "rownav_ros/mission_control.hpp"

namespace rownav::ros_bridge {

namespace {

std::string name(navigate::NavState nav) {
  return std::string(core::enum_name(nav));
}

/// States closed on odometry alone, whose time the NavStack watchdog budgets
/// (Navigator::effort): a pause there counts into that budget.
bool budgeted(navigate::NavState nav) {
  using navigate::NavState;
  return nav == NavState::exiting || nav == NavState::turning || nav == NavState::headland ||
         nav == NavState::entering;
}

}  // namespace

bool mission_ended(navigate::NavState nav) {
  return nav == navigate::NavState::done || nav == navigate::NavState::safe_stop;
}

MissionControl::MissionControl(bool autostart)
    : phase_(autostart ? MissionPhase::running : MissionPhase::waiting) {}

MissionAnswer MissionControl::start(navigate::NavState nav) {
  // A new mission from where the robot stands: the operator has put it at the start of the
  // plan's first corridor (issue 15: restart in place, no node restart).
  if (starts_new_mission(nav)) {
    const std::string was = phase_ == MissionPhase::stopped ? "stopped in " + name(nav) : name(nav);
    phase_ = MissionPhase::running;
    return {true, "new mission started (the last one " + was + ")", true};
  }
  switch (phase_) {
    case MissionPhase::running:
      return {true, "already running (" + name(nav) + ")"};
    case MissionPhase::paused:
      phase_ = MissionPhase::running;
      return {true, "resumed in " + name(nav)};
    default:
      phase_ = MissionPhase::running;
      return {true, "mission started in " + name(nav)};
  }
}

bool MissionControl::starts_new_mission(navigate::NavState nav) const {
  return phase_ == MissionPhase::stopped || mission_ended(nav);
}

MissionAnswer MissionControl::pause(navigate::NavState nav) {
  switch (phase_) {
    case MissionPhase::stopped:
      return {false, "mission stopped (command zero): nothing to pause"};
    case MissionPhase::waiting:
      return {true, "not started yet: command zero (~start begins the mission)"};
    case MissionPhase::paused:
      return {true, "already paused in " + name(nav)};
    default:
      break;
  }
  phase_ = MissionPhase::paused;
  std::string message = "paused in " + name(nav) + ": command zero, ~start resumes";
  if (budgeted(nav))
    message += " (a pause longer than this manoeuvre's time budget ends in a safe stop)";
  return {true, message};
}

MissionAnswer MissionControl::stop(navigate::NavState nav) {
  if (phase_ == MissionPhase::stopped) return {true, "already stopped"};
  phase_ = MissionPhase::stopped;
  return {true, "mission stopped in " + name(nav) +
                    ": command zero (~start begins a new mission from here)"};
}

std::string MissionControl::state(navigate::NavState nav) const {
  if (phase_ == MissionPhase::running || (phase_ != MissionPhase::stopped && mission_ended(nav)))
    return name(nav);
  return std::string(core::enum_name(phase_));
}

}  // namespace rownav::ros_bridge
