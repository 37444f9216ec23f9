#pragma once
/// @file
/// `lagrange report`, the derived table TRACKING.csv: per plant sample, the
/// true tracking error q − q_d (PLANT_TRUTH's q against the scenario's
/// reference, as summary.json judges it, not the controller's possibly noisy
/// view), its norm, and the reference rate q_d' beside the rate error. The
/// convergence time is computed by the logger's own metrics
/// (logger/tracking_metrics.hpp), so the plots' marker is summary.json's figure.

#include <optional>
#include <string>

#include "config/scenario.hpp"

namespace lagrange::tools {

/// Columns: tick, sim_time, q_error_norm, q_error[j], qdot_desired[j], qdot_error[j] (j from 1).
inline constexpr const char* kTrackingChannel = "TRACKING";

struct TrackingTable {
  long long rows = 0;                      ///< 0: no PLANT_TRUTH.csv to derive it from
  std::optional<double> convergence_time;  ///< first time after which ‖q~‖ < tolerance to the end [s]
  double end_time = 0.0;                   ///< the last sample's time [s]
  /// Why the table was not derived, when rows is 0 and PLANT_TRUTH.csv had
  /// rows (a sample the reference cannot be evaluated at; the file is removed).
  std::string problem;
  long long skipped = 0;  ///< rows without a finite tick and time, left out
};

/// Reads OUT_DIR/PLANT_TRUTH.csv, writes OUT_DIR/TRACKING.csv.
/// @throws RuntimeFault when the file cannot be written.
TrackingTable exportTracking(const config::Scenario& scenario, const std::string& out_dir);

}  // namespace lagrange::tools
