#pragma once
/// @file
/// Reading ODE bodies, shared by PlantSim and the robot kinds' builders
/// (inside plant/ only: this header includes ODE).

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lagrange::plant {

/// Whether the body's position, orientation and velocities are all finite.
inline bool bodyStateFinite(dBodyID body) {
  const dReal* w = dBodyGetAngularVel(body);
  const dReal* v = dBodyGetLinearVel(body);
  const dReal* p = dBodyGetPosition(body);
  const dReal* r = dBodyGetQuaternion(body);
  bool finite = true;
  for (int i = 0; i < 3; ++i)
    finite = finite && std::isfinite(w[i]) && std::isfinite(v[i]) && std::isfinite(p[i]);
  for (int i = 0; i < 4; ++i) finite = finite && std::isfinite(r[i]);
  return finite;
}

/// The distance between a hinge's anchor as its first body carries it and as
/// its second body (or the world) does [m].
inline double hingeSeparation(dJointID joint) {
  dVector3 a1, a2;
  dJointGetHingeAnchor(joint, a1);
  dJointGetHingeAnchor2(joint, a2);
  return std::sqrt((a1[0] - a2[0]) * (a1[0] - a2[0]) + (a1[1] - a2[1]) * (a1[1] - a2[1]) +
                   (a1[2] - a2[2]) * (a1[2] - a2[2]));
}

/// The largest hingeSeparation of `joints` [m] (ArmWorld::jointSeparation).
inline double largestHingeSeparation(const std::vector<dJointID>& joints) {
  double worst = 0.0;
  for (dJointID j : joints) worst = std::max(worst, hingeSeparation(j));
  return worst;
}

/// Whether every body's state is finite (ArmWorld::finite).
inline bool allBodiesFinite(const std::vector<dBodyID>& bodies) {
  return std::all_of(bodies.begin(), bodies.end(), bodyStateFinite);
}

/// sum of m_i g h_i over the bodies, h_i their centres' coordinate `up`
/// (0, 1, 2: x, y, z) against gravity [J].
inline double heightEnergy(const std::vector<dBodyID>& bodies, const std::vector<double>& mass,
                           double gravity, int up) {
  double e = 0.0;
  for (size_t i = 0; i < bodies.size(); ++i) e += mass[i] * gravity * dBodyGetPosition(bodies[i])[up];
  return e;
}

/// The body's rotation about the z axis [rad], in (-pi, pi]: the absolute
/// angle of a planar link (from the downward vertical) or of a rotor.
inline double zRotation(dBodyID body) {
  const dReal* r = dBodyGetRotation(body);  // 3x4 row-major
  return std::atan2(r[4], r[0]);
}

}  // namespace lagrange::plant
