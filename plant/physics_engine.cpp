#include "plant/physics_engine.hpp"

#include <map>
#include <stdexcept>

#include "plant/mujoco/mujoco_engine.hpp"
#include "plant/ode_engine.hpp"

namespace lagrange::plant {

namespace {
// The built-in engines first; registrations add to it during static initialisation.
std::map<std::string, EngineFactory>& factories() {
  static std::map<std::string, EngineFactory> all = {{"ode", makeOdeEngine}, {"mujoco", makeMujocoEngine}};
  return all;
}
}  // namespace

namespace {
void checkPerJoint(const Eigen::VectorXd& v, int n, const std::string& what) {
  if (v.size() == 0) return;
  if (v.size() != n)
    throw std::invalid_argument("plant: " + what + " has " + std::to_string(v.size()) +
                                " entries, expected " + std::to_string(n));
  if (!v.allFinite() || (v.array() < 0.0).any())
    throw std::invalid_argument("plant: " + what + " must be finite numbers >= 0");
}
}  // namespace

void checkJointPhysics(const JointPhysics& joints, int dof, bool flexible) {
  checkPerJoint(joints.damping, dof, "joint damping");
  checkPerJoint(joints.friction, dof, "joint friction");
  checkPerJoint(joints.rotor_damping, dof, "rotor damping");
  checkPerJoint(joints.rotor_friction, dof, "rotor friction");
  if (joints.lower.size() > 0 || joints.upper.size() > 0)
    if (joints.lower.size() != dof || joints.upper.size() != dof ||
        (joints.lower.array() > joints.upper.array()).any() || joints.lower.hasNaN() || joints.upper.hasNaN())
      throw std::invalid_argument("plant: joint stops need " + std::to_string(dof) +
                                  " pairs with lower <= upper");
  if (!flexible && (joints.rotor_damping.size() > 0 || joints.rotor_friction.size() > 0))
    throw std::invalid_argument("plant: rotor damping or friction without flexible joints");
}

void addPhysicsEngineFactory(const std::string& key, EngineFactory factory) {
  if (!factory) throw std::logic_error("plant: the physics engine '" + key + "' has no factory");
  if (!factories().emplace(key, std::move(factory)).second)
    throw std::logic_error("plant: a physics engine is registered as '" + key + "' already");
}

std::unique_ptr<PhysicsEngine> makePhysicsEngine(const EngineSetup& setup) {
  const auto it = factories().find(setup.choice.key);
  if (it == factories().end()) {
    std::string known;
    for (const std::string& k : physicsEngineKeys()) known += (known.empty() ? "" : ", ") + k;
    throw std::invalid_argument("plant.engine: no physics engine '" + setup.choice.key +
                                "' in this program; expected one of " + known);
  }
  return it->second(setup);
}

std::vector<std::string> physicsEngineKeys() {
  std::vector<std::string> keys = {"ode", "mujoco"};
  for (const auto& [key, factory] : factories())
    if (key != "ode" && key != "mujoco") keys.push_back(key);
  return keys;
}

}  // namespace lagrange::plant
