#include "model/bounds.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <random>

namespace lagrange::model {

double coriolisGain(const PlanarChain& chain, const Eigen::VectorXd& q) {
  const int n = chain.dof();
  const std::vector<Eigen::MatrixXd> ck = chain.coriolisPerVelocity(q);
  Eigen::MatrixXd row(n, n * n);
  for (int k = 0; k < n; ++k) row.block(0, k * n, n, n) = ck[k];
  return Eigen::JacobiSVD<Eigen::MatrixXd>(row).singularValues()(0);
}

double coriolisBound(const PlanarChain& chain) {
  const int n = chain.dof();
  if (n == 1) return 0.0;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  double sup = 0.0;
  if (n == 2) {
    constexpr int kGrid = 7200;
    for (int i = 0; i < kGrid; ++i) {
      q(1) = 2.0 * M_PI * i / kGrid;
      sup = std::max(sup, coriolisGain(chain, q));
    }
  } else {
    std::mt19937_64 rng(20261121);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
    for (int s = 0; s < 20000; ++s) {
      for (int i = 1; i < n; ++i) q(i) = angle(rng);
      sup = std::max(sup, coriolisGain(chain, q));
    }
  }
  return 1.05 * sup;
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
