#include "model/robot_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace lagrange::model {

namespace {
// The rotation taking z to `direction` (a cylinder's axis): Eigen's
// Quaternion::FromTwoVectors(UnitZ(), direction), written out because its
// branch for opposite vectors solves an SVD, 14 s of compile time for a corner
// case. The general case is Eigen's arithmetic step for step (the same bits).
// For a direction within 1e-12 of -z the axis is z x direction normalised (-x
// when that is zero, as Eigen's SVD finds): the same rotation as Eigen's to
// rounding or its mirror image there, whose axis sign the SVD leaves open; this
// one takes z onto the direction.
Eigen::Quaterniond zTo(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  // normalised twice, as the call it replaces did (its argument, then inside)
  const Eigen::Vector3d d = direction.normalized().normalized();
  const double c = d.dot(z);
  Eigen::Quaterniond q;
  if (c < -1.0 + Eigen::NumTraits<double>::dummy_precision()) {
    const Eigen::Vector3d normal = z.cross(d);
    const Eigen::Vector3d axis =
        normal.norm() > 0.0 ? Eigen::Vector3d(normal.normalized()) : Eigen::Vector3d(-1, 0, 0);
    const double w2 = (1.0 + std::max(c, -1.0)) * 0.5;
    q.w() = std::sqrt(w2);
    q.vec() = axis * std::sqrt(1.0 - w2);
    return q;
  }
  const Eigen::Vector3d axis = z.cross(d);
  const double s = std::sqrt((1.0 + c) * 2.0);
  const double invs = 1.0 / s;
  q.vec() = axis * invs;
  q.w() = s * 0.5;
  return q;
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
