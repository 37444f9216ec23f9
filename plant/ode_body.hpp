#pragma once
/// @file
/// Reading ODE bodies, shared by PlantSim and the robot kinds' builders
/// (inside plant/ only: this header includes ODE).

#include <ode/ode.h>

#include <cmath>

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

/// The body's rotation about the z axis [rad], in (-pi, pi]: the absolute
/// angle of a planar link (from the downward vertical) or of a rotor.
inline double zRotation(dBodyID body) {
  const dReal* r = dBodyGetRotation(body);  // 3x4 row-major
  return std::atan2(r[4], r[0]);
}

}  // namespace lagrange::plant
