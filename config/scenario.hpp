#pragma once
/// @file
/// The scenario: everything one run needs, loaded from YAML in layers
/// (defaults, then the file, then --set overrides) and validated before any
/// process starts. Every key is documented in docs/configuration.md.

#include <Eigen/Dense>
#include <algorithm>
#include <any>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model/flexible_joint.hpp"
#include "model/planar_chain.hpp"
#include "model/plant_perturbation.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"
#include "model/urdf_arm.hpp"
#include "transport/fault_rule.hpp"
#include "util/enum_names.hpp"
#include "util/error.hpp"

namespace lagrange::config {

/// A user-facing configuration error: names the key, the value and what was expected.
class ConfigError : public lagrange::BadInput {
 public:
  using lagrange::BadInput::BadInput;
};

struct InitialState {
  Eigen::VectorXd q;           ///< joint angles [rad]
  Eigen::VectorXd qdot;        ///< joint rates [rad/s]
  Eigen::VectorXd motor_q;     ///< flexible joints: q2(0) [rad] (default: the springs hold the links at rest)
  Eigen::VectorXd motor_qdot;  ///< flexible joints: q2'(0) [rad/s] (default: qdot)
};

/// robot.flexible: elastic joints driven by base-mounted rotors (eq. 595).
struct FlexibleConfig {
  model::FlexibleParams params;  ///< stiffness K, rotor_inertia J
  bool rate_sensor = false;      ///< the plant publishes q2' on PLANT_MOTOR
};

/// robot.<key> of a robot kind registered outside config (config/robot_kinds.hpp).
struct RegisteredRobot {
  std::string key;             ///< which kind
  std::any settings;           ///< what its section read
  model::RobotModelPtr model;  ///< its arm, built once when the scenario is read
};

/// robot.urdf: the serial chain of a URDF arm (model/urdf_arm.hpp).
struct UrdfRobotConfig {
  std::string file;  ///< where the document was read from, as written ("" when given inline)
  /// The URDF document itself. config.resolved.yaml and the SCENARIO message
  /// carry it, so a log replays without the file; when given, it is used and
  /// `file` is not read again.
  std::string xml;
  std::string base_link, tip_link;
};

/// MuJoCo's integrators (plant.mujoco_integrator).
enum class MujocoIntegrator { kRk4, kImplicit, kEuler };
inline constexpr util::EnumName<MujocoIntegrator> kMujocoIntegratorNames[] = {
    {MujocoIntegrator::kRk4, "rk4"},
    {MujocoIntegrator::kImplicit, "implicit"},
    {MujocoIntegrator::kEuler, "euler"}};

struct PlantConfig {
  /// "simulated": the plant process simulates the arm (the keys below);
  /// "external": a program from outside the project takes the plant's place
  /// over LCM (docs/external_programs.md) -- a simulator of one's own or a
  /// bridge to a real arm (docs/hardware.md) -- and of these keys only
  /// publish_rate applies.
  std::string type = "simulated";
  /// "external": its command line (argv; argv[0] absolute when given as a
  /// path) and the directory it starts in.
  std::vector<std::string> command;
  std::string working_directory;
  bool external() const { return type == "external"; }
  /// The physics engine (plant/physics_engine.hpp): "ode" (the design's,
  /// the default), "mujoco", or one a program registers (config/physics_engines.hpp).
  std::string engine = "ode";
  MujocoIntegrator mujoco_integrator = MujocoIntegrator::kRk4;  ///< with engine "mujoco" only
  double physics_step = 1e-4;                                   ///< the engine's step [s]
  double publish_rate = 1000;  ///< samples per second [Hz]; one tick per sample
  /// A limit on any body's angular rate [rad/s] the user sets: the plant stops
  /// the run when it is crossed. Unset (the default): no limit but the
  /// simulation's own (non-finite state, pi/2 per physics step).
  std::optional<double> max_rate;
  /// The arm's joints' viscous damping D_i [N m s/rad] and Coulomb friction
  /// F_i [N m] (plant/joint_effects.hpp). Unset: none, or with urdf_dynamics
  /// the URDF's <dynamics damping friction>; set, they override the URDF.
  std::optional<Eigen::VectorXd> joint_damping, joint_friction;
  bool urdf_dynamics = false;  ///< a URDF arm's <dynamics> in the plant
  /// The flexible joints' rotors' bearings: damping, Coulomb friction.
  std::optional<Eigen::VectorXd> rotor_damping, rotor_friction;
  bool joint_limits = false;  ///< a URDF arm's <limit lower upper> as hard stops
  /// A plant the controller does not know (model/plant_perturbation.hpp):
  /// a payload at the last link, seeded relative errors per link.
  std::optional<model::Payload> payload;
  std::optional<model::ModelError> model_error;
};

struct ActuatorConfig {
  int order = 0;  ///< m: integrator-chain order, 0..4
  /// Output updates per second [Hz]; a whole multiple of plant.publish_rate
  /// (0 in a fresh struct: resolved to plant.publish_rate when loaded).
  double rate = 0.0;
  std::optional<Eigen::VectorXd> saturation;  ///< per-joint |tau| limit [N m]
  Eigen::MatrixXd initial_state;              ///< m x n: xi_1(0) .. xi_m(0)
};

/// What the realtime plant does without a fresh torque (realtime.stale_torque):
/// hold the newest one for hold_periods more, or apply zero at once.
enum class StaleTorque { kHold, kZero };
inline constexpr util::EnumName<StaleTorque> kStaleTorqueNames[] = {{StaleTorque::kZero, "zero"},
                                                                    {StaleTorque::kHold, "hold"}};

struct ControllerConfig {
  /// A type registered by its own file (config/controller_params.hpp: the
  /// paper's theorem1, cascaded and flexible, the baselines, a user's), or
  /// "external"
  std::string type = "theorem1";
  /// A registered type's per-joint parameters, by key; empty for the others.
  std::map<std::string, Eigen::VectorXd> params;
  /// What a type with a section of its own read (ControllerSectionCodec);
  /// empty for the others. Its owner casts it (the paper's controllers:
  /// controller/paper_section.hpp).
  std::any settings;
  /// "external": the controller's command line (argv; argv[0] absolute when
  /// given as a path) and the directory it starts in (docs/external_programs.md).
  std::vector<std::string> command;
  std::string working_directory;
};

struct MetricsConfig {
  double tolerance = 1e-3;            ///< on ||q~|| [rad]
  double convergence_deadline = 5.0;  ///< stated metric: converged by this sim time [s]
  double xi_tolerance = 1e-2;         ///< on each ||xit_i|| of the cascaded controller [N m / s^(i-1)]
};

struct LockstepConfig {
  double retransmit_timeout = 0.05;  ///< wall time before the plant re-sends a tick [s]
  /// Ticks the plant may run ahead of the logger. Small, so that what is in
  /// flight (about 5 messages a tick) always fits the logger's socket buffer.
  int logger_window = 20;
  /// Wall time [s] a wait of the run may pass without progress -- the
  /// plant's for an answer or the logger, the handshake with every process
  /// -- before the plant stops the run, naming whom it waited for and what
  /// it saw instead (plant/stall_diagnosis.hpp).
  double stall_timeout = 10.0;
  /// The logger's nice value in lockstep (at least this; 0: as the others).
  /// It is off the tick's critical path -- the plant waits for it only
  /// logger_window ticks ahead -- so it yields the cores to the three
  /// processes on it (docs/performance.md).
  int logger_nice = 5;
};

/// Realtime mode: every process on its own fixed-rate loop.
struct RealtimeConfig {
  /// Ticks a torque may lag the plant's current tick before it is stale
  /// (its source position was published more than this many periods ago).
  int max_torque_age = 2;
  StaleTorque stale_torque = StaleTorque::kHold;
  int hold_periods = 20;
  double max_input_age = 0.005;  ///< controller and actuator skip inputs older than this [s]
  int priority = 50;             ///< SCHED_FIFO priority of the loops, 0 for the normal scheduler
  /// CPUs each process may run on (realtime.cpus.PROCESS), by process name;
  /// a process not named runs where the scheduler puts it.
  std::map<std::string, std::vector<int>> cpus;
};

/// What may happen to a datagram on one channel (faults.channels.NAME),
/// defined once where the transport applies it.
using ChannelFaults = transport::FaultRule;

/// Seeded fault injection on the sending side (faults.*).
struct FaultsConfig {
  uint64_t seed = 1;                              ///< each process draws from seed and its name
  std::map<std::string, ChannelFaults> channels;  ///< by channel name, or "all"
  /// By process name: the probability that a datagram reaching it is lost
  /// for it alone (faults.receivers.PROCESS.drop), every channel.
  std::map<std::string, double> receiver_drop;
};

/// One sensor per joint of one quantity (plant/joint_sensor.hpp).
struct JointSensorConfig {
  Eigen::VectorXd counts_per_revolution;  ///< per joint; 0: not quantised (angles only)
  Eigen::VectorXd noise_sigma;            ///< per joint [rad, or rad/s for rates]; 0: no noise
  int delay = 0;                          ///< whole samples
  /// The keys of registered sensor models (config/sensor_models.hpp) this
  /// sensor's section gives, by key; empty: none acts on it.
  std::map<std::string, Eigen::VectorXd> model_params;
};

/// The sensors in the plant's measurement path (sensors.*): PLANT_POSITION
/// carries the joint-angle readings, PLANT_RATE the velocity sensor's (only
/// when declared), PLANT_MOTOR the motor angles; PLANT_TRUTH the true values.
struct SensorsConfig {
  uint64_t seed = 1;                          ///< the noise's draws (each sensor its own stream)
  JointSensorConfig position;                 ///< joint angles
  std::optional<JointSensorConfig> velocity;  ///< a tachometer per joint; absent: no PLANT_RATE
  std::optional<JointSensorConfig> motor;     ///< motor angles of flexible joints; absent: exact
};

/// What `lagrange compare` runs (compare.*; docs/comparison.md).
struct CompareConfig {
  /// The controllers, in file order: type, and its keys as a YAML flow map
  /// (checked when `lagrange compare` builds its scenario).
  std::vector<std::pair<std::string, std::string>> controllers;
  std::string sweep_key;                  ///< compare.sweep.key; empty: no sweep
  std::vector<std::string> sweep_values;  ///< each as YAML text
};

/// What the launcher does when a process dies (supervision.*).
struct SupervisionConfig {
  /// Processes restarted when they die: "controller", "actuator". The plant
  /// (the simulated arm) and the logger (the log) cannot be restarted.
  std::vector<std::string> restart;
  int max_restarts = 3;  ///< per process; the next death stops the run
  /// [s] an answer (the controller's command to a position, the actuator's
  /// state to a command) slower than this is said on the terminal while it
  /// lasts and counted in summary.json `answers` (logger/answer_times.hpp).
  double slow_answer = 1.0;
  bool restarts(const std::string& process) const {
    return std::find(restart.begin(), restart.end(), process) != restart.end();
  }
};

/// How the processes are wired (docs/architecture.md): LCM processes in
/// lockstep or on fixed-rate loops, or one process without LCM.
enum class Mode { kLockstep, kRealtime, kInproc };
/// The spelling in scenario files and summary.json.
inline constexpr util::EnumName<Mode> kModeNames[] = {
    {Mode::kLockstep, "lockstep"}, {Mode::kRealtime, "realtime"}, {Mode::kInproc, "inproc"}};
inline const char* toString(Mode mode) { return util::nameOf(kModeNames, mode); }

struct Scenario {
  std::string name;
  std::string description;
  double duration = 10.0;  ///< simulated time [s]
  Mode mode = Mode::kLockstep;
  model::ChainParams robot;             ///< the planar chain (its gravity also a URDF arm's)
  std::optional<UrdfRobotConfig> urdf;  ///< robot.urdf: a URDF arm instead of robot.links
  /// The URDF arm, built once when the scenario is read (robotModel() returns it).
  std::shared_ptr<const model::UrdfArm> urdf_model;
  /// robot.<key> of a registered kind instead of robot.links or robot.urdf.
  std::optional<RegisteredRobot> registered_robot;
  std::optional<FlexibleConfig> flexible;  ///< robot.flexible
  InitialState initial_state;
  model::ReferenceParams reference;
  PlantConfig plant;
  ActuatorConfig actuator;
  ControllerConfig controller;
  MetricsConfig metrics;
  LockstepConfig lockstep;
  RealtimeConfig realtime;
  SupervisionConfig supervision;
  FaultsConfig faults;
  std::optional<SensorsConfig> sensors;  ///< absent: PLANT_POSITION carries the true angles
  std::optional<CompareConfig> compare;  ///< lagrange compare's section; lagrange run ignores it

  bool velocitySensor() const { return sensors && sensors->velocity; }
  int dof() const {
    if (registered_robot) return registered_robot->model->dof();
    return urdf_model ? urdf_model->dof() : static_cast<int>(robot.links.size());
  }
  double tickPeriod() const { return 1.0 / plant.publish_rate; }
  int substepsPerTick() const;
  /// Actuator output updates per plant period: actuator.rate / plant.publish_rate.
  int torqueStepsPerTick() const;
  long long lastTick() const;  ///< ticks run from 0 to lastTick() inclusive
  /// The rigid arm of `robot` (its links; for flexible joints without the springs).
  /// The one place a robot kind is built from the scenario.
  model::RobotModelPtr robotModel() const;
  /// The arm as the controller models it: the robot, plus joint springs K q
  /// for flexible joints (g(q1) + K q1 of Example 1; eq. 830c, 608).
  model::RobotModelPtr controlModel() const;
};

/// Parse and validate YAML text. `overrides` are "dotted.key=value" strings
/// (value in YAML syntax) applied before validation. `source` names the text
/// in messages (a file name).
/// @throws ConfigError naming the key, the value and what was expected.
Scenario parseScenario(const std::string& yaml_text, const std::string& source,
                       const std::vector<std::string>& overrides = {});

/// parseScenario of a log's SCENARIO (or a run folder's
/// config.resolved.yaml): the same checks but that an external controller's
/// or plant's program and folder exist -- they are the host's and the
/// time's the run was on, and no reader of a log runs them. A log is data:
/// no file it names is opened. Its arm's URDF is the copy the run recorded
/// (robot.urdf.xml, the file's text as the run read it), never
/// robot.urdf.file; a log whose robot.urdf lacks that copy is refused, as is
/// an `extends`. Only `overrides` (the user's --set) may name a URDF file:
/// `robot.urdf.file=F` replaces the recorded copy with F's text.
Scenario parseLoggedScenario(const std::string& yaml_text, const std::string& source,
                             const std::vector<std::string>& overrides = {});

/// Read a file and parse it. @throws ConfigError (also when unreadable).
Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides = {});

/// The fully resolved scenario (defaults included) as YAML; parseScenario of
/// it gives back the same scenario, bit for bit.
std::string toYaml(const Scenario& scenario);

}  // namespace lagrange::config
