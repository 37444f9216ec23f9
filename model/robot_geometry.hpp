#pragma once
/// @file
/// What a viewer needs to draw an arm: its frames as a kinematic tree and
/// simple shapes attached to them, sized from the model. Every robot kind
/// describes itself this way (RobotModel::geometry); the ROBOT_DESCRIPTION
/// message carries it, so a log can be drawn without its configuration.
///
/// Convention (URDF's joint convention): the pose of frame i in the world is
///   T_i = T_parent(i) * Trans(origin_xyz_i) * Rot(origin_quat_i) * Rot(axis_i, q[joint_i]),
/// with T_-1 the identity (the base) and no rotation when joint_i is -1 (a
/// fixed frame). A shape's pose in its frame is Trans(xyz) * Rot(quat).

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace lagrange::model {

struct GeometryFrame {
  int parent = -1;                                       ///< index of the parent frame; -1: the base
  int joint = -1;                                        ///< index into q rotating this frame; -1: fixed
  Eigen::Vector3d origin_xyz = Eigen::Vector3d::Zero();  ///< [m], in the parent frame
  Eigen::Quaterniond origin_quat = Eigen::Quaterniond::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit joint axis in this frame
};

struct GeometryShape {
  enum class Type { kBox = 0, kCylinder = 1, kSphere = 2 };
  int frame = -1;  ///< the frame it moves with; -1: the base
  Type type = Type::kSphere;
  /// Box: edge lengths x, y, z. Cylinder (along its local z): radius, length, 0.
  /// Sphere: radius, 0, 0. [m]
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();
};

struct RobotGeometry {
  std::vector<GeometryFrame> frames;  ///< parents before children
  std::vector<GeometryShape> shapes;
  int tip_frame = -1;                                 ///< the frame the tip point is fixed in
  Eigen::Vector3d tip_xyz = Eigen::Vector3d::Zero();  ///< the tip in tip_frame [m]
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();      ///< against gravity, for the camera
  /// The normal of the plane of motion for a planar arm (the camera looks
  /// along it); zero for an arm that moves in 3D.
  Eigen::Vector3d plane_normal = Eigen::Vector3d::Zero();
};

/// Adds the shapes every kind draws the same way, sized from the frames: a
/// rod from each frame's origin to each child's (when they are apart), a
/// disc along each joint's axis, a sphere at the tip. Radii scale with the
/// arm's reach (the sum of the offsets between frames).
void addSkeletonShapes(RobotGeometry& geometry);

}  // namespace lagrange::model
