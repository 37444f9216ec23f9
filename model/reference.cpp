#include "model/reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lagrange::model {

const char* toString(ReferenceType type) { return type == ReferenceType::kSine ? "sine" : "smooth_sine"; }

Reference::Reference(ReferenceParams params) : params_(std::move(params)) {
  const auto n = params_.offset.size();
  if (n < 1) throw std::invalid_argument("reference: offset must have at least one entry");
  auto check = [n](const Eigen::VectorXd& v, const char* name) {
    if (v.size() != n)
      throw std::invalid_argument(std::string("reference: ") + name + " has " + std::to_string(v.size()) +
                                  " entries, expected " + std::to_string(n) + " (one per joint)");
    if (!v.allFinite()) throw std::invalid_argument(std::string("reference: ") + name + " must be finite");
  };
  check(params_.amplitude, "amplitude");
  check(params_.frequency, "frequency");
  check(params_.phase, "phase");
  check(params_.offset, "offset");
  if ((params_.frequency.array() < 0.0).any())
    throw std::invalid_argument("reference: frequency must be >= 0");
  if (params_.type == ReferenceType::kSmoothSine) {
    check(params_.alpha, "alpha");
    if ((params_.alpha.array() <= 0.0).any())
      throw std::invalid_argument("reference: alpha must be > 0 for smooth_sine");
  }
}

namespace {
// d^k/dt^k of f(t) = b + c sin(w t + p).
double sineDerivative(double b, double c, double w, double p, int k, double t) {
  const double x = w * t + p;
  const double wk = std::pow(w, k);
  switch (k % 4) {
    case 0:
      return (k == 0 ? b : 0.0) + c * wk * std::sin(x);
    case 1:
      return c * wk * std::cos(x);
    case 2:
      return -c * wk * std::sin(x);
    default:
      return -c * wk * std::cos(x);
  }
}

// d^k/dt^k of s(t) = 1 - exp(-alpha t^3), k = 0..4 (Faa di Bruno on exp(p(t))).
double smoothStartDerivative(double alpha, int k, double t) {
  const double e = std::exp(-alpha * t * t * t);
  const double p1 = -3.0 * alpha * t * t, p2 = -6.0 * alpha * t, p3 = -6.0 * alpha;
  switch (k) {
    case 0:
      return 1.0 - e;
    case 1:
      return -p1 * e;
    case 2:
      return -(p2 + p1 * p1) * e;
    case 3:
      return -(p3 + 3.0 * p1 * p2 + p1 * p1 * p1) * e;
    default:
      return -(4.0 * p1 * p3 + 3.0 * p2 * p2 + 6.0 * p1 * p1 * p2 + p1 * p1 * p1 * p1) * e;
  }
}

constexpr int kBinomial[5][5] = {
    {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
}  // namespace

double Reference::jointDerivative(int joint, int order, double t) const {
  if (order < 0 || order > 4) throw std::invalid_argument("reference: derivative order must be 0..4");
  const double b = params_.offset(joint), c = params_.amplitude(joint);
  const double w = params_.frequency(joint), p = params_.phase(joint);
  if (params_.type == ReferenceType::kSine) return sineDerivative(b, c, w, p, order, t);
  // Leibniz rule on s(t) f(t).
  const double alpha = params_.alpha(joint);
  double sum = 0.0;
  for (int j = 0; j <= order; ++j)
    sum +=
        kBinomial[order][j] * smoothStartDerivative(alpha, j, t) * sineDerivative(b, c, w, p, order - j, t);
  return sum;
}

ReferenceSample Reference::evaluate(double t, int max_order) const {
  if (max_order < 0 || max_order > 4) throw std::invalid_argument("reference: max_order must be 0..4");
  ReferenceSample s;
  for (int k = 0; k <= max_order; ++k) {
    s.derivative[k].resize(dof());
    for (int i = 0; i < dof(); ++i) s.derivative[k](i) = jointDerivative(i, k, t);
  }
  return s;
}

double Reference::jointBound(int joint, int order) const {
  const double b = params_.offset(joint), c = params_.amplitude(joint);
  const double w = params_.frequency(joint);
  const double stationary = (order == 0 ? std::abs(b) : 0.0) + std::abs(c) * std::pow(w, order);
  if (params_.type == ReferenceType::kSine) return stationary;

  const double alpha = params_.alpha(joint);
  const double settle = std::cbrt(std::log(1e12) / alpha);  // exp(-alpha t^3) < 1e-12 after it
  const double period = w > 0.0 ? 2.0 * M_PI / w : settle;
  const double horizon = settle + period;
  // Resolve both the transient (time scale alpha^-1/3) and the oscillation.
  const double step = std::min(period, std::cbrt(1.0 / alpha)) / 20000.0;
  double sampled = 0.0;
  for (double t = 0.0; t <= horizon; t += step)
    sampled = std::max(sampled, std::abs(jointDerivative(joint, order, t)));
  return 1.02 * std::max(sampled, stationary);
}

}  // namespace lagrange::model
