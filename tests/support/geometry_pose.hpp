#pragma once
// Poses of a RobotGeometry's frames, composed as robot_description_t says
// (the rule the viewer's page follows), for checking a description against a
// kind's own forward kinematics.

#include <Eigen/Geometry>

#include "model/robot_geometry.hpp"

namespace lagrange::testing {

inline Eigen::Isometry3d framePose(const model::RobotGeometry& g, int frame, const Eigen::VectorXd& q) {
  if (frame < 0) return Eigen::Isometry3d::Identity();
  const model::GeometryFrame& f = g.frames.at(static_cast<size_t>(frame));
  Eigen::Isometry3d pose = framePose(g, f.parent, q);
  pose.translate(f.origin_xyz);
  pose.rotate(f.origin_quat);
  if (f.joint >= 0) pose.rotate(Eigen::AngleAxisd(q(f.joint), f.axis));
  return pose;
}

inline Eigen::Vector3d geometryTip(const model::RobotGeometry& g, const Eigen::VectorXd& q) {
  return framePose(g, g.tip_frame, q) * g.tip_xyz;
}

}  // namespace lagrange::testing
