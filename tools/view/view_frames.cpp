#include "tools/view/view_frames.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {
bool finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}
bool unit(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x * x;
  return std::abs(sum - 1.0) < 1e-6;
}
bool rows(const std::vector<std::vector<double>>& m, size_t count, size_t width, bool must_be_unit = false) {
  if (m.size() != count) return false;
  for (const auto& row : m)
    if (row.size() != width || !finite(row) || (must_be_unit && !unit(row))) return false;
  return true;
}
}  // namespace

std::string descriptionProblem(const lagrange::robot_description_t& d) {
  const size_t frames = d.frame_parent.size(), shapes = d.shape_frame.size();
  const int32_t n = d.num_joints;
  if (n < 1 || d.joint_names.size() != static_cast<size_t>(n)) return "num_joints does not match joint_names";
  if (static_cast<int32_t>(frames) != d.num_frames || d.frame_joint.size() != frames || frames == 0)
    return "num_frames does not match its arrays (or is 0)";
  if (static_cast<int32_t>(shapes) != d.num_shapes || d.shape_type.size() != shapes)
    return "num_shapes does not match its arrays";
  if (!rows(d.frame_xyz, frames, 3) || !rows(d.frame_quat, frames, 4, true) ||
      !rows(d.frame_axis, frames, 3, true))
    return "a frame's origin, orientation or axis is not finite, or not of unit length";
  for (size_t i = 0; i < frames; ++i) {
    if (d.frame_parent[i] < -1 || d.frame_parent[i] >= static_cast<int32_t>(i))
      return "frame " + std::to_string(i) + "'s parent does not come before it";
    if (d.frame_joint[i] < -1 || d.frame_joint[i] >= n)
      return "frame " + std::to_string(i) + "'s joint is not one of the " + std::to_string(n) + " joints";
  }
  if (!rows(d.shape_size, shapes, 3) || !rows(d.shape_xyz, shapes, 3) || !rows(d.shape_quat, shapes, 4, true))
    return "a shape's size or pose is not finite, or its orientation not of unit length";
  for (size_t s = 0; s < shapes; ++s) {
    if (d.shape_frame[s] < -1 || d.shape_frame[s] >= static_cast<int32_t>(frames))
      return "shape " + std::to_string(s) + "'s frame does not exist";
    if (d.shape_type[s] < 0 || d.shape_type[s] > 2)
      return "shape " + std::to_string(s) + "'s type is unknown";
  }
  if (d.tip_frame < -1 || d.tip_frame >= static_cast<int32_t>(frames)) return "tip_frame does not exist";
  for (double x : d.tip_xyz)
    if (!std::isfinite(x)) return "tip_xyz is not finite";
  return "";
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

nlohmann::json envelopeJson(const std::vector<ViewFrame>& frames, const std::vector<size_t>& sent) {
  nlohmann::json tau_min = nlohmann::json::array(), tau_max = nlohmann::json::array(),
                 error_min = nlohmann::json::array(), error_max = nlohmann::json::array();
  for (size_t i = 0; i < sent.size(); ++i) {
    const size_t end = i + 1 < sent.size() ? sent[i + 1] : sent[i] + 1;
    std::vector<double> lo = frames[sent[i]].tau, hi = lo;
    double e_lo = std::numeric_limits<double>::infinity(), e_hi = -e_lo;
    for (size_t k = sent[i]; k < end && k < frames.size(); ++k) {
      const ViewFrame& f = frames[k];
      for (size_t j = 0; j < lo.size() && j < f.tau.size(); ++j)
        lo[j] = std::fmin(lo[j], f.tau[j]), hi[j] = std::fmax(hi[j], f.tau[j]);  // a NaN is passed over
      if (std::isfinite(f.error_norm))
        e_lo = std::min(e_lo, f.error_norm), e_hi = std::max(e_hi, f.error_norm);
    }
    tau_min.push_back(lo);
    tau_max.push_back(hi);
    error_min.push_back(std::isfinite(e_lo) ? nlohmann::json(e_lo) : nlohmann::json());
    error_max.push_back(std::isfinite(e_hi) ? nlohmann::json(e_hi) : nlohmann::json());
  }
  return {{"tau_min", tau_min}, {"tau_max", tau_max}, {"error_min", error_min}, {"error_max", error_max}};
}

}  // namespace lagrange::tools
