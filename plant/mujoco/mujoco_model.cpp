#include "plant/mujoco/mujoco_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace lagrange::plant {

namespace {

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string vec(const Eigen::Vector3d& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

const char* integratorName(MujocoIntegrator i) {
  switch (i) {
    case MujocoIntegrator::kImplicit:
      return "implicit";
    case MujocoIntegrator::kEuler:
      return "Euler";
    case MujocoIntegrator::kRk4:
      break;
  }
  return "RK4";
}

// A joint's own attributes: damping, friction, a stop on either side (MJCF's
// range is two-sided: an open side is a limit no motion reaches).
std::string jointPhysics(const JointPhysics& j, int i) {
  std::string out;
  if (j.damping.size() > 0 && j.damping(i) > 0.0) out += " damping=\"" + num(j.damping(i)) + "\"";
  if (j.friction.size() > 0 && j.friction(i) > 0.0) out += " frictionloss=\"" + num(j.friction(i)) + "\"";
  if (j.lower.size() > 0 && (std::isfinite(j.lower(i)) || std::isfinite(j.upper(i)))) {
    // An open side: 1e10 rad (1.6e9 turns, past any run's reach), or past the
    // other side's bound if that lies further out, so the range stays ordered.
    const double lo = std::isfinite(j.lower(i)) ? j.lower(i) : -std::max(1e10, std::abs(j.upper(i)) + 1.0);
    const double hi = std::isfinite(j.upper(i)) ? j.upper(i) : std::max(1e10, std::abs(j.lower(i)) + 1.0);
    out += " limited=\"true\" range=\"" + num(lo) + " " + num(hi) + "\"";
  }
  return out;
}

std::string rotorPhysics(const JointPhysics& j, int i) {
  std::string out;
  if (j.rotor_damping.size() > 0 && j.rotor_damping(i) > 0.0)
    out += " damping=\"" + num(j.rotor_damping(i)) + "\"";
  if (j.rotor_friction.size() > 0 && j.rotor_friction(i) > 0.0)
    out += " frictionloss=\"" + num(j.rotor_friction(i)) + "\"";
  return out;
}

}  // namespace

std::string mujocoModelXml(const ArmBodies& arm, const EngineSetup& setup) {
  const int n = static_cast<int>(arm.bodies.size());
  std::ostringstream x;
  x << "<mujoco model=\"lagrange\">\n"
    << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
    << "  <option timestep=\"" << num(setup.physics_step) << "\" integrator=\""
    << integratorName(setup.choice.mujoco_integrator) << "\" gravity=\"" << vec(arm.gravity) << "\">\n"
    << "    <flag contact=\"disable\" energy=\"enable\"/>\n"
    << "  </option>\n"
    // Friction and stops as stiff as MuJoCo advises (a time constant of two
    // steps, impedance up to 0.999): its defaults let a link creep through
    // friction at 2 % of its free motion and 0.09 rad into a stop
    // (docs/extending.md, "Physics engines").
    << "  <default><joint solreffriction=\"" << num(2 * setup.physics_step)
    << " 1\" solimpfriction=\"0.99 0.999 0.001\" solreflimit=\"" << num(2 * setup.physics_step)
    << " 1\" solimplimit=\"0.99 0.999 0.001\"/></default>\n"
    << "  <worldbody>\n";
  // Each body's frame at its joint's anchor, with the base's axes (the
  // bodies are given at q = 0): a child sits at its anchor minus its parent's.
  Eigen::Vector3d parent_anchor = Eigen::Vector3d::Zero();
  std::string indent = "    ";
  for (int i = 0; i < n; ++i) {
    const ChainBody& b = arm.bodies[static_cast<size_t>(i)];
    const Eigen::Matrix3d& in = b.inertia;
    x << indent << "<body name=\"link" << i + 1 << "\" pos=\"" << vec(b.joint_anchor - parent_anchor)
      << "\">\n"
      << indent << "  <joint name=\"joint" << i + 1 << "\" type=\"hinge\" pos=\"0 0 0\" axis=\""
      << vec(b.joint_axis) << "\"" << jointPhysics(setup.joints, i) << "/>\n"
      << indent << "  <inertial pos=\"" << vec(b.com - b.joint_anchor) << "\" mass=\"" << num(b.mass)
      << "\" fullinertia=\"" << num(in(0, 0)) << " " << num(in(1, 1)) << " " << num(in(2, 2)) << " "
      << num(in(0, 1)) << " " << num(in(0, 2)) << " " << num(in(1, 2)) << "\"/>\n";
    parent_anchor = b.joint_anchor;
    indent += "  ";
  }
  for (int i = n - 1; i >= 0; --i) {
    indent.resize(indent.size() - 2);
    x << indent << "</body>\n";
  }
  if (setup.flexible) {
    // Below the links, as ODE's rotors; the hinge holds the mass, so its value does not matter.
    for (int i = 0; i < n; ++i) {
      const double j = setup.flexible->rotor_inertia(i);
      x << "    <body name=\"rotor" << i + 1 << "\" pos=\"0 0 " << num(-0.1 * (i + 1)) << "\">\n"
        << "      <joint name=\"rotor" << i + 1 << "\" type=\"hinge\" pos=\"0 0 0\" axis=\"0 0 1\""
        << rotorPhysics(setup.joints, i) << "/>\n"
        << "      <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"" << num(j) << " " << num(j) << " "
        << num(j) << "\"/>\n"
        << "    </body>\n";
    }
  }
  x << "  </worldbody>\n";
  if (setup.flexible) {
    // Tendon length q2_i - q1_i, force -K_i (q2_i - q1_i) along it: on the
    // rotor -K (q2 - q1), on the link +K (q2 - q1) -- the spring of eq. (flexible).
    x << "  <tendon>\n";
    for (int i = 0; i < n; ++i)
      x << "    <fixed name=\"spring" << i + 1 << "\" stiffness=\"" << num(setup.flexible->stiffness(i))
        << "\" springlength=\"0\">\n"
        << "      <joint joint=\"rotor" << i + 1 << "\" coef=\"1\"/>\n"
        << "      <joint joint=\"joint" << i + 1 << "\" coef=\"-1\"/>\n"
        << "    </fixed>\n";
    x << "  </tendon>\n";
  }
  x << "</mujoco>\n";
  return x.str();
}

}  // namespace lagrange::plant
