#pragma once
/// @file
/// The export's /tracking group: the true tracking error per tick, the same
/// columns as Python's Run.tracking (python/lagrange/log.py) -- PLANT_TRUTH.q
/// less CONTROL_COMMAND.q_desired, joined by header.tick (the first intact
/// copy of each tick, the row the channels' groups hold), t = tick /
/// plant.publish_rate of the log's scenario, q and q_desired, the error and
/// its norm, and for a controller with a chain CONTROL_COMMAND.xi_error, the
/// stages' errors (docs/export.md).
///
/// Two passes, as the export reads the log: the first learns which ticks
/// both channels have (and with how many joints), so the datasets are made
/// whole; the second fills rows as the two halves of a tick arrive, holding
/// only the halves still waiting for their other (a tick's truth and its
/// command are a few events apart in a log) and blocks of finished rows.

#include <H5Cpp.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lagrange::tools {

/// The correctly rounded sum of `values`, as Python's math.fsum (Shewchuk's
/// partials, with its half-even correction), so that ‖q - q_d‖ here is
/// Run.tracking's bit for bit for any number of joints. A non-finite value
/// makes the sum its plain sum (inf or NaN).
double correctlyRoundedSum(const std::vector<double>& values);

class TrackingExport {
 public:
  /// Pass 1: an intact copy of PLANT_TRUTH (its q's size) or CONTROL_COMMAND
  /// (its q_desired's) at `tick`, in the log's order (the first copy counts).
  void seeTruth(int64_t tick, size_t joints) { truth_seen_.emplace_back(tick, joints); }
  void seeCommand(int64_t tick, size_t joints) { command_seen_.emplace_back(tick, joints); }

  /// Between the passes: the rows, `joints` wide (PLANT_TRUTH/q's width);
  /// `stages` of xi_error (CONTROL_COMMAND's first message's; 0: no chain, no
  /// xi_error); `period` is 1 / plant.publish_rate, absent when no scenario
  /// reads (no `t`).
  void plan(size_t joints, size_t stages, std::optional<double> period);

  /// After plan(): whether the log has both channels (else there is no /tracking; why()).
  bool wanted() const { return any_truth_ && any_command_ && joints_ > 0; }
  std::string why() const;

  /// Creates /tracking and its datasets, `rows()` rows each.
  void create(H5::H5File& file);

  /// Pass 2: the first intact copy of a tick (the channel's row).
  void truth(int64_t tick, const std::vector<double>& q) { half(tick, q, true); }
  void command(int64_t tick, const std::vector<double>& q_desired,
               const std::vector<std::vector<double>>& xi_error);

  /// Writes the finished rows held.
  void flush();

  size_t rows() const { return ticks_.size(); }
  /// What the group leaves out (counted in its attributes too).
  std::vector<std::string> warnings() const;

 private:
  struct Halves {
    std::vector<double> q, q_desired, xi_error;  // xi_error: stages x joints, row-major
    bool has_q = false, has_q_desired = false;
  };
  void half(int64_t tick, const std::vector<double>& values, bool is_truth,
            std::vector<double> xi_error = {});

  std::vector<std::pair<int64_t, size_t>> truth_seen_, command_seen_;
  std::vector<int64_t> ticks_;  // joined, sorted: the rows
  size_t joints_ = 0, stages_ = 0;
  long long xi_misshapen_ = 0;
  bool any_truth_ = false, any_command_ = false;
  std::optional<double> period_;
  long long unjoined_truth_ = 0, unjoined_command_ = 0, mismatched_ = 0, other_width_ = 0;
  std::map<size_t, Halves> pending_;  // rows waiting for their other half
  std::map<size_t, Halves> done_;     // rows with both, not yet written
  H5::Group group_;
  H5::DataSet tick_, t_, q_, q_desired_, q_error_, error_norm_, xi_error_;
};

}  // namespace lagrange::tools
