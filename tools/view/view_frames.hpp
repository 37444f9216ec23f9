#pragma once
/// @file
/// What `lagrange view` draws, per tick: the arm's angles (PLANT_TRUTH), the
/// reference the controller tracked (CONTROL_COMMAND.q_desired, the ghost
/// arm), the rotor angles of flexible joints (PLANT_MOTOR) and the applied
/// torques, joined by tick from messages that arrive in any order. The same
/// assembler serves a log and a running scenario. No I/O.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/robot_description_t.hpp"

namespace lagrange::tools {

struct ViewFrame {
  int64_t tick = 0;
  double t = 0.0;                 ///< sim_time [s]
  std::vector<double> q;          ///< joint (link) angles [rad]
  std::vector<double> q_desired;  ///< the reference the controller reported; empty before any command
  std::vector<double> motor;      ///< rotor angles of flexible joints (as measured); empty otherwise
  std::vector<double> tau;        ///< applied joint torques [N m]
  double error_norm = 0.0;        ///< |q - q_desired| [rad]; NaN without a reference
};

class FrameAssembler {
 public:
  void add(const lagrange::plant_truth_t& truth);
  void add(const lagrange::control_command_t& command);
  void add(const lagrange::plant_motor_t& motor);

  /// The frames whose tick is complete, in tick order: every tick older than
  /// the newest PLANT_TRUTH (its command and motor sample had their chance to
  /// arrive), or every tick with a PLANT_TRUTH when `all`. A tick whose
  /// command or motor sample never came takes the newest one before it.
  std::vector<ViewFrame> take(bool all);

 private:
  struct Pending {
    std::optional<lagrange::plant_truth_t> truth;
    std::vector<double> q_desired, motor;
  };
  std::map<int64_t, Pending> pending_;
  int64_t newest_truth_ = -1;
  int64_t emitted_ = -1;  ///< the last tick taken
  std::vector<double> last_desired_, last_motor_;
};

/// Why a ROBOT_DESCRIPTION cannot be drawn ("" when it can): sizes that
/// disagree with their counts, a parent that does not come before its frame,
/// a joint, frame or shape type out of range, a number that is not finite, an
/// axis or quaternion that is not of unit length. The page builds its scene
/// from it as it is, so the server checks it first (it may come off the network).
std::string descriptionProblem(const lagrange::robot_description_t& d);

/// ROBOT_DESCRIPTION as the page reads it (field names as in the message).
nlohmann::json descriptionJson(const lagrange::robot_description_t& d);

/// Frames as columns: {"t": [...], "q": [[...], ...], "q_desired", "motor",
/// "tau", "error_norm"}; a missing value is null.
nlohmann::json framesJson(const std::vector<ViewFrame>& frames);
/// For a log sent as every k-th frame: per frame sent (`sent`, ascending
/// indices into `frames`), the min and max of each torque and of the error
/// norm over the frames it stands for (up to the next one sent), so the
/// page's plots keep every peak: {"tau_min": [[per joint] per frame sent],
/// "tau_max", "error_min", "error_max" (null where no reference)}.
nlohmann::json envelopeJson(const std::vector<ViewFrame>& frames, const std::vector<size_t>& sent);

}  // namespace lagrange::tools
