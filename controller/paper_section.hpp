#pragma once
/// @file
/// The config section of the paper's controllers (theorem1, cascaded,
/// flexible): gains, stages, filter starts and the motor rate's source, read
/// and written here and kept in the scenario's ControllerConfig::settings
/// (config/controller_params.hpp). config itself knows none of it.

#include <Eigen/Dense>
#include <any>
#include <optional>
#include <string>
#include <vector>

#include "config/controller_params.hpp"
#include "config/fields.hpp"
#include "config/key_table.hpp"
#include "config/scenario.hpp"
#include "controller/paper_gains.hpp"
#include "util/enum_names.hpp"

namespace lagrange::controller {

/// Where the flexible controller's q2' comes from (controller.motor_rate):
/// the motor's rate sensor, or a dirty derivative a s / (s + a) of q2 with
/// a = motor_rate_pole.
enum class MotorRate { kMeasured, kFiltered };
inline constexpr util::EnumName<MotorRate> kMotorRateNames[] = {{MotorRate::kMeasured, "measured"},
                                                                {MotorRate::kFiltered, "filtered"}};

/// controller.* of the paper's controllers.
struct PaperSettings {
  Theorem1Gains gains;             ///< stage 0 (kp0, kd0, a0, b0 for "cascaded")
  std::vector<StageGains> stages;  ///< "cascaded": stages 1..m; "flexible": 2
  /// qc(0); empty means "bumpless": qc(0) = -b q~(0), so theta(0) = 0.
  std::optional<Eigen::VectorXd> initial_filter_state;
  /// Per stage i = 1..m, how its filter starts (stages[i].initial_filter_state,
  /// stages[i].initial_zeta); default: qc_i(0) = zeta_i(0) = 0.
  std::vector<StageStart> stage_starts;
  /// "flexible": where q2' comes from (unset for the other types).
  std::optional<MotorRate> motor_rate;
  Eigen::VectorXd motor_rate_pole;  ///< [1/s], "filtered" only
};

/// theorem1, cascaded or flexible.
bool isPaperType(const std::string& type);

/// The settings of a scenario whose controller.type is one of the paper's
/// (empty settings, as in a Scenario built in code, read as defaults).
/// @throws std::logic_error for another type's scenario.
const PaperSettings& paperSettings(const config::Scenario& s);
/// The same, to change them (a Scenario built or varied in code); fills
/// empty settings with defaults first.
PaperSettings& paperSettings(config::Scenario& s);

/// The section's reader and writer, and its keys' rows (variant "paper"),
/// for the paper controllers' registration (paper_controllers.cpp).
config::ControllerSectionCodec paperSectionCodec();
std::vector<config::KeyInfo> paperKeyRows();
/// controller.kp, kd, a, b; controller.stages[i] the same.
const config::Fields<Theorem1Gains>& paperGainFields();
const config::Fields<StageGains>& stageGainFields();

}  // namespace lagrange::controller
