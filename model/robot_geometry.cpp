#include "model/robot_geometry.hpp"

#include <algorithm>

namespace lagrange::model {

namespace {
// The rotation taking z to `direction` (a cylinder's axis).
Eigen::Quaterniond zTo(const Eigen::Vector3d& direction) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), direction.normalized());
}
}  // namespace

void addSkeletonShapes(RobotGeometry& g) {
  double reach = 0.0;
  for (const GeometryFrame& f : g.frames) reach += f.origin_xyz.norm();
  reach += g.tip_xyz.norm();
  // A rod's radius: thin against the arm, never zero for an arm of offsets 0.
  const double radius = std::max(0.03 * reach, 1e-3);
  auto rod = [&](int frame, const Eigen::Vector3d& to) {
    if (to.norm() < 1e-9) return;
    GeometryShape s;
    s.frame = frame;
    s.type = GeometryShape::Type::kCylinder;
    s.size = {radius, to.norm(), 0.0};
    s.xyz = to / 2.0;
    s.quat = zTo(to);
    g.shapes.push_back(s);
  };
  for (int i = 0; i < static_cast<int>(g.frames.size()); ++i) {
    const GeometryFrame& f = g.frames[i];
    rod(f.parent, f.origin_xyz);
    if (f.joint < 0) continue;
    GeometryShape disc;
    disc.frame = i;
    disc.type = GeometryShape::Type::kCylinder;
    disc.size = {2.0 * radius, 3.0 * radius, 0.0};
    disc.quat = zTo(f.axis);
    g.shapes.push_back(disc);
  }
  rod(g.tip_frame, g.tip_xyz);
  GeometryShape tip;
  tip.frame = g.tip_frame;
  tip.type = GeometryShape::Type::kSphere;
  tip.size = {1.5 * radius, 0.0, 0.0};
  tip.xyz = g.tip_xyz;
  g.shapes.push_back(tip);
}

}  // namespace lagrange::model
