#include "config/robot_description_lcm.hpp"

namespace lagrange::config {

namespace {
std::vector<double> values(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
std::vector<double> values(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }
void copy(const Eigen::Vector3d& v, double (&out)[3]) {
  for (int k = 0; k < 3; ++k) out[k] = v(k);
}
}  // namespace

lagrange::robot_description_t robotDescriptionMessage(const Scenario& s) {
  const model::RobotModelPtr arm = s.robotModel();
  const model::RobotGeometry g = arm->geometry();
  lagrange::robot_description_t m;
  m.kind = arm->kind();
  m.joint_names = arm->jointNames();
  m.num_joints = static_cast<int32_t>(m.joint_names.size());
  m.flexible = s.flexible.has_value();
  m.num_frames = static_cast<int32_t>(g.frames.size());
  for (const model::GeometryFrame& f : g.frames) {
    m.frame_parent.push_back(f.parent);
    m.frame_joint.push_back(f.joint);
    m.frame_xyz.push_back(values(f.origin_xyz));
    m.frame_quat.push_back(values(f.origin_quat));
    m.frame_axis.push_back(values(f.axis));
  }
  m.num_shapes = static_cast<int32_t>(g.shapes.size());
  for (const model::GeometryShape& shape : g.shapes) {
    m.shape_frame.push_back(shape.frame);
    m.shape_type.push_back(static_cast<int8_t>(shape.type));
    m.shape_size.push_back(values(shape.size));
    m.shape_xyz.push_back(values(shape.xyz));
    m.shape_quat.push_back(values(shape.quat));
  }
  m.tip_frame = g.tip_frame;
  copy(g.tip_xyz, m.tip_xyz);
  copy(g.up, m.up);
  copy(g.plane_normal, m.plane_normal);
  return m;
}

}  // namespace lagrange::config
