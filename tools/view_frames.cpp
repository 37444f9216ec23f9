#include "tools/view_frames.hpp"

#include <cmath>

namespace lagrange::tools {

void FrameAssembler::add(const lagrange::plant_truth_t& truth) {
  const int64_t tick = truth.header.tick;
  if (tick <= emitted_) return;  // a retransmission of a tick already drawn
  pending_[tick].truth = truth;
  newest_truth_ = std::max(newest_truth_, tick);
}

void FrameAssembler::add(const lagrange::control_command_t& command) {
  const int64_t tick = command.input_position_tick;
  if (tick <= emitted_) return;
  pending_[tick].q_desired = command.q_desired;
}

void FrameAssembler::add(const lagrange::plant_motor_t& motor) {
  const int64_t tick = motor.header.tick;
  if (tick <= emitted_) return;
  pending_[tick].motor = motor.q;
}

std::vector<ViewFrame> FrameAssembler::take(bool all) {
  std::vector<ViewFrame> frames;
  const int64_t last = all ? newest_truth_ : newest_truth_ - 1;
  for (auto it = pending_.begin(); it != pending_.end() && it->first <= last;) {
    Pending& p = it->second;
    if (!p.q_desired.empty()) last_desired_ = std::move(p.q_desired);
    if (!p.motor.empty()) last_motor_ = std::move(p.motor);
    if (p.truth) {
      const lagrange::plant_truth_t& truth = *p.truth;
      ViewFrame f;
      f.tick = it->first;
      f.t = truth.header.sim_time;
      f.q = truth.q;
      f.tau = truth.tau_applied;
      f.q_desired = last_desired_;
      f.motor = last_motor_;
      f.error_norm = std::nan("");
      if (f.q_desired.size() == f.q.size()) {
        double sum = 0.0;
        for (size_t i = 0; i < f.q.size(); ++i) sum += (f.q[i] - f.q_desired[i]) * (f.q[i] - f.q_desired[i]);
        f.error_norm = std::sqrt(sum);
      }
      frames.push_back(std::move(f));
    }
    emitted_ = it->first;
    it = pending_.erase(it);
  }
  return frames;
}

nlohmann::json descriptionJson(const lagrange::robot_description_t& d) {
  return {{"kind", d.kind},
          {"joint_names", d.joint_names},
          {"flexible", d.flexible != 0},
          {"frame_parent", d.frame_parent},
          {"frame_joint", d.frame_joint},
          {"frame_xyz", d.frame_xyz},
          {"frame_quat", d.frame_quat},
          {"frame_axis", d.frame_axis},
          {"shape_frame", d.shape_frame},
          {"shape_type", d.shape_type},
          {"shape_size", d.shape_size},
          {"shape_xyz", d.shape_xyz},
          {"shape_quat", d.shape_quat},
          {"tip_frame", d.tip_frame},
          {"tip_xyz", d.tip_xyz},
          {"up", d.up},
          {"plane_normal", d.plane_normal}};
}

namespace {
nlohmann::json vectorOrNull(const std::vector<double>& v) {
  return v.empty() ? nlohmann::json() : nlohmann::json(v);
}
}  // namespace

nlohmann::json framesJson(const std::vector<ViewFrame>& frames) {
  nlohmann::json t = nlohmann::json::array(), q = nlohmann::json::array(),
                 q_desired = nlohmann::json::array(), motor = nlohmann::json::array(),
                 tau = nlohmann::json::array(), error_norm = nlohmann::json::array();
  for (const ViewFrame& f : frames) {
    t.push_back(f.t);
    q.push_back(f.q);
    q_desired.push_back(vectorOrNull(f.q_desired));
    motor.push_back(vectorOrNull(f.motor));
    tau.push_back(f.tau);
    error_norm.push_back(std::isfinite(f.error_norm) ? nlohmann::json(f.error_norm) : nlohmann::json());
  }
  return {{"t", t},         {"q", q},     {"q_desired", q_desired},
          {"motor", motor}, {"tau", tau}, {"error_norm", error_norm}};
}

}  // namespace lagrange::tools
