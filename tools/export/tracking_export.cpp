#include "tools/export/tracking_export.hpp"

#include <algorithm>
#include <cmath>

#include "tools/export/hdf5_write.hpp"

namespace lagrange::tools {

namespace {

// Finished rows held before they are written (as the channels' groups).
constexpr size_t kTrackingHeldRows = 4096;

// The first copy of each tick, in tick order: sorted stably, so that of a
// tick's copies the log's first stays first.
std::vector<std::pair<int64_t, size_t>> firstCopies(std::vector<std::pair<int64_t, size_t>> seen) {
  std::stable_sort(seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  seen.erase(
      std::unique(seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
      seen.end());
  return seen;
}

}  // namespace

double correctlyRoundedSum(const std::vector<double>& values) {
  // CPython's math_fsum (Modules/mathmodule.c), for finite values.
  double plain = 0.0;
  for (double v : values) plain += v;
  for (double v : values)
    if (!std::isfinite(v)) return plain;
  std::vector<double> partials;
  for (double x : values) {
    size_t i = 0;
    for (double y : partials) {
      if (std::fabs(x) < std::fabs(y)) std::swap(x, y);
      const double hi = x + y;
      const double lo = y - (hi - x);
      if (lo != 0.0) partials[i++] = lo;
      x = hi;
    }
    partials.resize(i);
    if (!std::isfinite(x)) return x;  // an intermediate overflow (Python raises OverflowError)
    if (x != 0.0) partials.push_back(x);
  }
  double hi = 0.0, lo = 0.0;
  size_t n = partials.size();
  if (n > 0) {
    hi = partials[--n];
    while (n > 0) {
      const double x = hi, y = partials[--n];
      hi = x + y;
      lo = y - (hi - x);
      if (lo != 0.0) break;
    }
    // Half-even rounding across partials: a lower partial of the same sign
    // as the rounding error tips a tie.
    if (n > 0 && ((lo < 0.0 && partials[n - 1] < 0.0) || (lo > 0.0 && partials[n - 1] > 0.0))) {
      const double y = lo * 2.0, x = hi + y;
      if (y == x - hi) hi = x;
    }
  }
  return hi;
}

void TrackingExport::plan(size_t joints, size_t stages, std::optional<double> period) {
  joints_ = joints;
  stages_ = stages;
  period_ = period;
  const auto truth = firstCopies(std::move(truth_seen_)), command = firstCopies(std::move(command_seen_));
  truth_seen_ = {}, command_seen_ = {};  // done with
  any_truth_ = !truth.empty(), any_command_ = !command.empty();
  long long both = 0;
  auto a = truth.begin(), b = command.begin();
  while (a != truth.end() && b != command.end()) {
    if (a->first < b->first) {
      ++a;
    } else if (b->first < a->first) {
      ++b;
    } else {
      ++both;
      if (a->second != b->second)
        ++mismatched_;  // as Run.tracking: left out
      else if (a->second != joints_)
        ++other_width_;  // a row HDF5 cannot hold beside the others
      else
        ticks_.push_back(a->first);
      ++a, ++b;
    }
  }
  unjoined_truth_ = static_cast<long long>(truth.size()) - both;
  unjoined_command_ = static_cast<long long>(command.size()) - both;
}

std::string TrackingExport::why() const {
  if (!any_truth_ && !any_command_) return "the log has neither PLANT_TRUTH nor CONTROL_COMMAND";
  if (!any_truth_) return "the log has no PLANT_TRUTH";
  if (!any_command_) return "the log has no CONTROL_COMMAND";
  return joints_ == 0 ? "PLANT_TRUTH's q has no joints" : "";
}

void TrackingExport::create(H5::H5File& file) {
  using hdf5::dataset;
  const hsize_t n = ticks_.size(), j = joints_;
  group_ = file.createGroup("/tracking");
  hdf5::textAttribute(
      group_, "description",
      "the true tracking error per tick, as Run.tracking: PLANT_TRUTH.q - CONTROL_COMMAND.q_desired "
      "joined by header.tick");
  if (period_) {
    const double rate = 1.0 / *period_;
    hdf5::numberAttribute(group_, "publish_rate", H5::PredType::NATIVE_DOUBLE, &rate);
  }
  for (const auto& [name, count] :
       {std::pair<const char*, long long>{"unjoined_PLANT_TRUTH", unjoined_truth_},
        {"unjoined_CONTROL_COMMAND", unjoined_command_},
        {"mismatched", mismatched_},
        {"other_joint_count", other_width_}})
    hdf5::numberAttribute(group_, name, H5::PredType::NATIVE_INT64, &count);
  tick_ = dataset(group_, "tick", H5::PredType::NATIVE_INT64, {n}, "tick", "header.tick of both messages");
  if (period_)
    t_ = dataset(group_, "t", H5::PredType::NATIVE_DOUBLE, {n}, "s", "tick x (1 / plant.publish_rate)");
  q_ = dataset(group_, "q", H5::PredType::NATIVE_DOUBLE, {n, j}, "rad", "PLANT_TRUTH.q");
  q_desired_ =
      dataset(group_, "q_desired", H5::PredType::NATIVE_DOUBLE, {n, j}, "rad", "CONTROL_COMMAND.q_desired");
  q_error_ = dataset(group_, "q_error", H5::PredType::NATIVE_DOUBLE, {n, j}, "rad", "q - q_desired");
  error_norm_ = dataset(group_, "error_norm", H5::PredType::NATIVE_DOUBLE, {n}, "rad", "||q - q_desired||");
  if (stages_ > 0)
    xi_error_ =
        dataset(group_, "xi_error", H5::PredType::NATIVE_DOUBLE, {n, stages_, j}, "N m / s^(k-1) for stage k",
                "CONTROL_COMMAND.xi_error: the chain's stage errors, stage 1 first");
  if (!period_) hdf5::textAttribute(group_, "t", "left out: the log's scenario does not read");
}

void TrackingExport::command(int64_t tick, const std::vector<double>& q_desired,
                             const std::vector<std::vector<double>>& xi_error) {
  std::vector<double> flat;
  if (stages_ > 0) {
    // A row of another shape than the first message's: NaN, as the channel's own group has it.
    bool shaped = xi_error.size() == stages_;
    for (const auto& stage : xi_error) shaped = shaped && stage.size() == joints_;
    if (!shaped) ++xi_misshapen_;
    for (size_t i = 0; i < stages_; ++i)
      for (size_t j = 0; j < joints_; ++j) flat.push_back(shaped ? xi_error[i][j] : std::nan(""));
  }
  half(tick, q_desired, false, std::move(flat));
}

void TrackingExport::half(int64_t tick, const std::vector<double>& values, bool is_truth,
                          std::vector<double> xi_error) {
  const auto at = std::lower_bound(ticks_.begin(), ticks_.end(), tick);
  // Not a joined tick, or a row of another width (the log grew between the passes).
  if (at == ticks_.end() || *at != tick || values.size() != joints_) return;
  const size_t row = static_cast<size_t>(at - ticks_.begin());
  if (done_.count(row)) return;
  Halves& h = pending_[row];
  if (is_truth ? h.has_q : h.has_q_desired) return;
  (is_truth ? h.q : h.q_desired) = values;
  if (!is_truth) h.xi_error = std::move(xi_error);
  (is_truth ? h.has_q : h.has_q_desired) = true;
  if (!h.has_q || !h.has_q_desired) return;
  done_[row] = std::move(h);
  pending_.erase(row);
  if (done_.size() >= kTrackingHeldRows) flush();
}

void TrackingExport::flush() {
  while (!done_.empty()) {
    const size_t first = done_.begin()->first;
    size_t count = 0;
    for (auto it = done_.begin(); it != done_.end() && it->first == first + count; ++it) ++count;
    std::vector<int64_t> ticks;
    std::vector<double> times, q, q_desired, q_error, norms, xi;
    auto it = done_.begin();
    for (size_t k = 0; k < count; ++k, ++it) {
      const int64_t tick = ticks_[it->first];
      const Halves& h = it->second;
      std::vector<double> squares;
      ticks.push_back(tick);
      if (period_)
        times.push_back(static_cast<double>(tick) * *period_);  // Run.tracking: tick * (1.0 / rate)
      for (size_t j = 0; j < joints_; ++j) {
        const double e = h.q[j] - h.q_desired[j];
        q.push_back(h.q[j]), q_desired.push_back(h.q_desired[j]), q_error.push_back(e);
        squares.push_back(e * e);
      }
      norms.push_back(std::sqrt(correctlyRoundedSum(squares)));
      xi.insert(xi.end(), h.xi_error.begin(), h.xi_error.end());
    }
    hdf5::writeRows(tick_, H5::PredType::NATIVE_INT64, ticks.data(), first, count);
    if (period_) hdf5::writeRows(t_, H5::PredType::NATIVE_DOUBLE, times.data(), first, count);
    hdf5::writeRows(q_, H5::PredType::NATIVE_DOUBLE, q.data(), first, count);
    hdf5::writeRows(q_desired_, H5::PredType::NATIVE_DOUBLE, q_desired.data(), first, count);
    hdf5::writeRows(q_error_, H5::PredType::NATIVE_DOUBLE, q_error.data(), first, count);
    hdf5::writeRows(error_norm_, H5::PredType::NATIVE_DOUBLE, norms.data(), first, count);
    if (stages_ > 0) hdf5::writeRows(xi_error_, H5::PredType::NATIVE_DOUBLE, xi.data(), first, count);
    done_.erase(done_.begin(), it);
  }
}

std::vector<std::string> TrackingExport::warnings() const {
  std::vector<std::string> w;
  if (!wanted()) return {"no /tracking group: " + why()};
  if (!period_)
    w.push_back("/tracking has no t: the log's scenario does not read (its publish_rate is unknown)");
  if (mismatched_ > 0)
    w.push_back(
        "/tracking: " + std::to_string(mismatched_) +
        " ticks whose PLANT_TRUTH.q and CONTROL_COMMAND.q_desired hold different numbers of joints are "
        "left out (attribute mismatched)");
  if (other_width_ > 0)
    w.push_back("/tracking: " + std::to_string(other_width_) + " ticks of another number of joints than " +
                std::to_string(joints_) + " (PLANT_TRUTH/q's) are left out (attribute other_joint_count)");
  if (xi_misshapen_ > 0)
    w.push_back("/tracking: " + std::to_string(xi_misshapen_) + " commands' xi_error of another shape than " +
                std::to_string(stages_) + " stages x " + std::to_string(joints_) +
                " joints; their xi_error is NaN");
  if (!pending_.empty())
    w.push_back("/tracking: " + std::to_string(pending_.size()) +
                " rows lack a half the first pass saw (the log changed while it was read); they hold zeros");
  return w;
}

}  // namespace lagrange::tools
