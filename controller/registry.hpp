#pragma once
/// @file
/// The controllers a scenario can name in controller.type, each registered
/// once, in its own file, with one definition -- the paper's three
/// (theorem1, cascaded, flexible) in paper_controllers.cpp, the baselines in
/// baselines.cpp, a new controller likewise:
///
///     const bool registered = lagrange::controller::registerControllerKind(withTunable(
///         {"my_pd", {{"kp", true, "stiffness [N m/rad]"}}, [](const config::Scenario& s) { ... }},
///         {{"kp", true, 1e-2, 1e5, 100.0}}));  // the gains `lagrange tune` searches
///
/// Its keys are then valid in controller.*, read into
/// ScenarioConfig::controller.params, written back to config.resolved.yaml,
/// and every wiring (lockstep, realtime, inproc, replay) runs it. Every
/// process of a run must know the type: build the project's process mains
/// with the file linked in (tests/CMakeLists.txt does this for the test
/// controller) -- see docs/extending.md, "Adding a controller".

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "config/controller_params.hpp"
#include "config/scenario.hpp"
#include "controller/controller.hpp"
#include "controller/gain_report.hpp"
#include "controller/input_assembly.hpp"

namespace lagrange::controller {

/// A gain `lagrange tune` may search (tools/tune/, docs/tuning.md): a key of
/// controller.* holding positive numbers, searched on a log scale between
/// `lower` and `upper`.
struct TunableGain {
  std::string name;       ///< its key in controller.* (or in each stage's, per_stage)
  bool per_joint = true;  ///< one value per joint; false: one value for every joint
  double lower = 0.0;     ///< the range searched: 0 < lower < upper
  double upper = 0.0;
  /// Where the search starts when the scenario's value lies outside the
  /// range (within it: the scenario's value).
  double fallback = 1.0;
  /// A key of each of controller.stages[i] (a chain's later stages: the
  /// paper's cascaded and flexible controllers), searched for every stage
  /// the scenario has; false: a key of controller.* itself.
  bool per_stage = false;
};

struct ControllerKind {
  std::string type;                           ///< controller.type
  std::vector<config::ControllerParam> keys;  ///< its keys in controller.*
  /// Builds it from a validated scenario (controller.params holds its keys).
  std::function<std::unique_ptr<Controller>(const config::Scenario&)> make;
  /// Its gain check; empty: no stability condition is known, and the report
  /// says so (GainReport::unchecked).
  std::function<GainReport(const config::Scenario&, bool sampled_data)> report;
  /// It regulates to a constant q_d: the config refuses any other reference.
  bool set_point = false;
  /// It reads measured joint rates (Needs::joint_rates): the config refuses
  /// a scenario without a velocity sensor.
  bool measures_velocity = false;
  /// A section of its own instead of `keys` (config/controller_params.hpp),
  /// and how it is named when it drives elastic joints; the paper's use them.
  config::ControllerSectionCodec section = {};
  std::string elastic_joints_title = {};
  int listing = 100;  ///< where messages and docs list it: lower first, then by name
  /// The gains `lagrange tune` searches; every registered controller
  /// declares at least one (registerControllerKind refuses none).
  std::vector<TunableGain> tunable = {};
};

/// `kind` with `tunable` as its tunable gains (for a kind built in one
/// brace-initialiser).
ControllerKind withTunable(ControllerKind kind, std::vector<TunableGain> tunable);

/// Registers a controller. Returns true, so that a file can register from
/// a namespace-scope initialiser. @throws std::logic_error if the type is
/// taken, or its tunable gains are none or one has no valid range
/// (0 < lower < upper, lower <= fallback <= upper).
bool registerControllerKind(ControllerKind kind);

/// The tunable gains of a registered controller.type (none for external).
/// @throws std::logic_error for a type nobody registered.
const std::vector<TunableGain>& tunableGains(const std::string& type);

/// The controller the scenario names. @throws std::logic_error for a type
/// nobody registered (the config reader rejects those first).
std::unique_ptr<Controller> makeController(const config::Scenario& s);

/// The input rule for a controller with these needs in scenario s: xi(0) from
/// actuator.initial_state, and (flexible joints) the initial motor state as
/// realtime's sample before the first PLANT_MOTOR.
InputAssembly makeInputAssembly(const config::Scenario& s, const Needs& needs);

}  // namespace lagrange::controller
