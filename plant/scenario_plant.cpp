#include "plant/scenario_plant.hpp"

#include <limits>

#include "model/urdf_arm.hpp"
#include "plant/robot_kinds.hpp"
#include "plant/sensor_models.hpp"

namespace lagrange::plant {

JointPhysics jointPhysicsFor(const config::Scenario& s) {
  JointPhysics out;
  const config::PlantConfig& p = s.plant;
  const int n = s.dof();
  if (s.urdf_model && p.urdf_dynamics) {
    const auto& joints = s.urdf_model->jointProperties();
    out.damping = out.friction = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      out.damping(i) = joints[static_cast<size_t>(i)].damping;
      out.friction(i) = joints[static_cast<size_t>(i)].friction;
    }
  }
  if (p.joint_damping) out.damping = *p.joint_damping;
  if (p.joint_friction) out.friction = *p.joint_friction;
  if (p.rotor_damping) out.rotor_damping = *p.rotor_damping;
  if (p.rotor_friction) out.rotor_friction = *p.rotor_friction;
  if (s.urdf_model && p.joint_limits) {
    const auto& joints = s.urdf_model->jointProperties();
    out.lower = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
    out.upper = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
    for (int i = 0; i < n; ++i) {
      const model::UrdfJointProperties& j = joints[static_cast<size_t>(i)];
      if (j.lower && j.upper) {
        out.lower(i) = *j.lower;
        out.upper(i) = *j.upper;
      }
    }
  }
  return out;
}

EngineChoice engineFor(const config::Scenario& s) {
  EngineChoice c;
  c.key = s.plant.engine;
  switch (s.plant.mujoco_integrator) {
    case config::MujocoIntegrator::kRk4:
      c.mujoco_integrator = MujocoIntegrator::kRk4;
      break;
    case config::MujocoIntegrator::kImplicit:
      c.mujoco_integrator = MujocoIntegrator::kImplicit;
      break;
    case config::MujocoIntegrator::kEuler:
      c.mujoco_integrator = MujocoIntegrator::kEuler;
      break;
  }
  return c;
}

PlantSim plantFor(const config::Scenario& s) {
  return PlantSim(
      armBuilderFor(s),
      {s.initial_state.q, s.initial_state.qdot, s.initial_state.motor_q, s.initial_state.motor_qdot},
      s.plant.physics_step, s.flexible ? std::optional(s.flexible->params) : std::nullopt, s.plant.max_rate,
      jointPhysicsFor(s), engineFor(s));
}

void checkPlantBuilds(const config::Scenario& s) {
  try {
    plantFor(s);
  } catch (const std::invalid_argument& e) {
    throw config::ConfigError(e.what());
  }
}

namespace {
// Each sensor draws from its own stream: the seed plus a multiple of the
// golden-ratio constant (SplitMix64's increment), so adding a sensor never
// changes another's draws, and the joint-angle sensor's are those of seed.
JointSensor sensorOf(int joints, const config::JointSensorConfig& c, uint64_t seed, uint64_t stream) {
  const uint64_t own = seed + stream * 0x9E3779B97F4A7C15ULL;
  return JointSensor(joints,
                     {c.counts_per_revolution, c.noise_sigma, c.delay, own, sensorEffects(c, joints, own)});
}
}  // namespace

ScenarioSensors sensorsFor(const config::Scenario& s) {
  const int n = s.dof();
  if (!s.sensors) return {JointSensor(n), std::nullopt, std::nullopt};
  const config::SensorsConfig& c = *s.sensors;
  ScenarioSensors out{sensorOf(n, c.position, c.seed, 0), std::nullopt, std::nullopt};
  if (c.velocity) out.velocity = sensorOf(n, *c.velocity, c.seed, 1);
  if (c.motor) out.motor = sensorOf(n, *c.motor, c.seed, 2);
  return out;
}

PlantSample measureTick(const config::Scenario& s, ScenarioSensors& sensors, const PlantSim& sim,
                        int64_t tick, double sim_time, const Eigen::VectorXd& tau_applied,
                        TorqueInput input) {
  const PlantState st = sim.state();
  const PlantEnergy e = sim.energy();
  PlantSample out = plantSample(tick, sim_time, st.q, st.qdot, tau_applied, e.kinetic, e.potential, input,
                                sensors.position.measure(st.q));
  if (sensors.velocity) out.rate = rateMessage(tick, sim_time, sensors.velocity->measure(st.qdot));
  if (s.flexible) {
    const Eigen::VectorXd motor_q = sensors.motor ? sensors.motor->measure(st.motor_q) : st.motor_q;
    out.motor = motorMessage(tick, sim_time, motor_q, st.motor_qdot, s.flexible->rate_sensor);
  }
  return out;
}

}  // namespace lagrange::plant
