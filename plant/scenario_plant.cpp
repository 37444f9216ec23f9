#include "plant/scenario_plant.hpp"

#include "plant/robot_kinds.hpp"
#include "plant/sensor_models.hpp"

namespace lagrange::plant {

PlantSim plantFor(const config::Scenario& s) {
  return PlantSim(
      armBuilderFor(s),
      {s.initial_state.q, s.initial_state.qdot, s.initial_state.motor_q, s.initial_state.motor_qdot},
      s.plant.physics_step, s.flexible ? std::optional(s.flexible->params) : std::nullopt, s.plant.max_rate);
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
