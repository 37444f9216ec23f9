#include "model/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "model/spectra.hpp"

namespace lagrange::model {

double coriolisGain(const RobotModel& model, const Eigen::VectorXd& q) {
  const int n = model.dof();
  const std::vector<Eigen::MatrixXd> ck = model.coriolisPerVelocity(q);
  Eigen::MatrixXd row(n, n * n);
  for (int k = 0; k < n; ++k) row.block(0, k * n, n, n) = ck[k];
  return largestSingularValue(row);
}

std::optional<double> coriolisBound(const RobotModel& model) {
  const int n = model.dof();
  const std::optional<std::vector<CoriolisTerm>> closed_form = model.coriolisTerms();
  if (!closed_form) return std::nullopt;
  const std::vector<CoriolisTerm>& terms = *closed_form;
  if (terms.empty()) return 0.0;
  double triangle = 0.0;
  Eigen::MatrixXd all(n, static_cast<Eigen::Index>(n) * n * static_cast<Eigen::Index>(terms.size()));
  for (size_t p = 0; p < terms.size(); ++p) {
    Eigen::MatrixXd row(n, n * n);
    for (int k = 0; k < n; ++k) row.block(0, k * n, n, n) = terms[p].per_velocity[k];
    triangle += largestSingularValue(row);
    all.block(0, static_cast<Eigen::Index>(p) * n * n, n, n * n) = row;
  }
  const double cauchy_schwarz = std::sqrt(static_cast<double>(terms.size())) * largestSingularValue(all);
  return std::min(triangle, cauchy_schwarz);
}

double coriolisLargestFound(const RobotModel& model) {
  const int n = model.dof();
  if (n == 1) return 0.0;
  // An evaluation of G costs O(n^4). Up to kFullSearchJoints the search is
  // the full one; past it the evaluations shrink as (kFullSearchJoints / n)^4,
  // so that the search costs what it costs at that size (seconds) and the
  // estimate from below gets weaker instead of the check taking minutes
  // (16 joints: 1250 samples and at most as many compass steps from one start).
  constexpr int kFullSearchJoints = 8;
  const bool full = n <= kFullSearchJoints;
  const long samples =
      full ? 20000 : std::max(100L, std::lround(20000.0 * std::pow(double(kFullSearchJoints) / n, 4)));
  long compass_budget = full ? std::numeric_limits<long>::max() : samples;
  std::vector<std::pair<double, Eigen::VectorXd>> found;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  if (n == 2) {
    constexpr int kGrid = 7200;
    for (int i = 0; i < kGrid; ++i) {
      q(1) = 2.0 * M_PI * i / kGrid;
      found.emplace_back(coriolisGain(model, q), q);
    }
  } else {
    std::mt19937_64 rng(20261121);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
    for (long s = 0; s < samples; ++s) {
      for (int i = 1; i < n; ++i) q(i) = angle(rng);
      found.emplace_back(coriolisGain(model, q), q);
    }
  }
  const size_t starts = std::min<size_t>(full ? 4 : 1, found.size());
  std::partial_sort(found.begin(), found.begin() + static_cast<long>(starts), found.end(),
                    [](const auto& x, const auto& y) { return x.first > y.first; });
  double best = found.front().first;
  for (size_t s = 0; s < starts; ++s) {
    auto [value, at] = found[s];
    // Compass search on the relative angles: a step up along any axis is taken,
    // the step halves when none is, down to 1e-9 rad.
    for (double step = 0.1; step > 1e-9 && compass_budget > 0;) {
      bool moved = false;
      for (int i = 1; i < n; ++i) {
        for (const double sign : {1.0, -1.0}) {
          Eigen::VectorXd trial = at;
          trial(i) += sign * step;
          const double v = coriolisGain(model, trial);
          --compass_budget;
          if (v > value) value = v, at = trial, moved = true;
        }
      }
      if (!moved) step /= 2.0;
    }
    best = std::max(best, value);
  }
  return best;
}

double referenceBound(const Reference& reference) {
  double kdelta = 0.0;
  for (int order = 0; order <= 2; ++order) {
    double sq = 0.0;
    for (int i = 0; i < reference.dof(); ++i) sq += std::pow(reference.jointBound(i, order), 2);
    kdelta = std::max(kdelta, std::sqrt(sq));
  }
  return kdelta;
}

}  // namespace lagrange::model
