#include "plant/robot_kinds.hpp"

#include <map>
#include <stdexcept>

#include "config/physics_engines.hpp"
#include "plant/planar_chain_world.hpp"
#include "plant/urdf_arm_world.hpp"

namespace lagrange::plant {

namespace {
// A function-local static: registrations run during static initialisation.
std::map<std::string, std::function<ArmBuilder(const std::any&, double)>>& worlds() {
  static std::map<std::string, std::function<ArmBuilder(const std::any&, double)>> all;
  return all;
}
}  // namespace

bool registerRobotKind(RobotKind kind) {
  if (!kind.world)
    throw std::logic_error("plant::registerRobotKind: robot." + kind.section.key + " has no world builder");
  const std::string key = kind.section.key;
  config::registerRobotKindSection(std::move(kind.section));  // refuses a key taken
  worlds().emplace(key, std::move(kind.world));
  return true;
}

bool registerPhysicsEngine(const std::string& key, EngineFactory factory) {
  if (!factory) throw std::logic_error("plant::registerPhysicsEngine: '" + key + "' has no factory");
  config::registerPhysicsEngineKey(key);  // refuses a key taken
  addPhysicsEngineFactory(key, std::move(factory));
  return true;
}

ArmBuilder armBuilderFor(const config::Scenario& s) {
  if (s.registered_robot) {
    const auto it = worlds().find(s.registered_robot->key);
    if (it == worlds().end())
      throw std::logic_error("plant::armBuilderFor: robot." + s.registered_robot->key +
                             " was read by config but has no world builder in this program");
    return it->second(s.registered_robot->settings, s.robot.gravity);
  }
  // The plant's arm: the nominal one, or with the payload and model error
  // the controller does not know of.
  const std::optional<model::Payload>& payload = s.plant.payload;
  const std::optional<model::ModelError>& error = s.plant.model_error;
  if (s.urdf_model)
    return payload || error ? urdfArmWorld(model::perturbedBodies(*s.urdf_model, payload, error).bodies,
                                           s.urdf_model->spec().gravity)
                            : urdfArmWorld(s.urdf_model);
  return planarChainWorld(payload || error ? model::perturbedChain(s.robot, payload, error).params : s.robot);
}

}  // namespace lagrange::plant
