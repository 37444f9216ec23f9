#include "model/bounds.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace lagrange::model {

double coriolisGain(const RobotModel& model, const Eigen::VectorXd& q) {
  const int n = model.dof();
  const std::vector<Eigen::MatrixXd> ck = model.coriolisPerVelocity(q);
  Eigen::MatrixXd row(n, n * n);
  for (int k = 0; k < n; ++k) row.block(0, k * n, n, n) = ck[k];
  return Eigen::JacobiSVD<Eigen::MatrixXd>(row).singularValues()(0);
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
    triangle += Eigen::JacobiSVD<Eigen::MatrixXd>(row).singularValues()(0);
    all.block(0, static_cast<Eigen::Index>(p) * n * n, n, n * n) = row;
  }
  const double cauchy_schwarz = std::sqrt(static_cast<double>(terms.size())) *
                                Eigen::JacobiSVD<Eigen::MatrixXd>(all).singularValues()(0);
  return std::min(triangle, cauchy_schwarz);
}

double coriolisLargestFound(const RobotModel& model) {
  const int n = model.dof();
  if (n == 1) return 0.0;
  std::vector<std::pair<double, Eigen::VectorXd>> samples;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  if (n == 2) {
    constexpr int kGrid = 7200;
    for (int i = 0; i < kGrid; ++i) {
      q(1) = 2.0 * M_PI * i / kGrid;
      samples.emplace_back(coriolisGain(model, q), q);
    }
  } else {
    std::mt19937_64 rng(20261121);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
    for (int s = 0; s < 20000; ++s) {
      for (int i = 1; i < n; ++i) q(i) = angle(rng);
      samples.emplace_back(coriolisGain(model, q), q);
    }
  }
  const size_t starts = std::min<size_t>(4, samples.size());
  std::partial_sort(samples.begin(), samples.begin() + static_cast<long>(starts), samples.end(),
                    [](const auto& x, const auto& y) { return x.first > y.first; });
  double best = samples.front().first;
  for (size_t s = 0; s < starts; ++s) {
    auto [value, at] = samples[s];
    // Compass search on the relative angles: a step up along any axis is taken,
    // the step halves when none is, down to 1e-9 rad.
    for (double step = 0.1; step > 1e-9;) {
      bool moved = false;
      for (int i = 1; i < n; ++i) {
        for (const double sign : {1.0, -1.0}) {
          Eigen::VectorXd trial = at;
          trial(i) += sign * step;
          const double v = coriolisGain(model, trial);
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
