#include "model/reference.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace lagrange::model {

struct FreeMotionTable {
  std::vector<Eigen::VectorXd> nodes;         ///< [q; q'] every kFreeStep seconds from 0
  std::vector<std::array<double, 3>> bounds;  ///< per joint, orders 0..2
  uint64_t id = nextId();                     ///< never reused in the process (freeState's memo)

  static uint64_t nextId() {
    static std::atomic<uint64_t> next{1};
    return next++;
  }
};

namespace {
constexpr double kFreeStep = 1e-4;

// The free motions integrated and still held by a Reference, by what decides
// them: the model object (constant once built: robot_model.hpp), the initial
// state and the horizon, bit for bit. A sampled-data check builds a
// scenario's reference in every simulation it runs, twice (the controller's,
// the metrics'): a 10 s free motion is 100 000 RK4 steps of the arm's forward
// dynamics, a quarter of a flexible arm's simulation, the same each time.
// Weak pointers: a table lives as long as a Reference holds it, so this keeps
// no memory of its own; a model ended and another built at its address does
// not match (the first one's weak pointer has expired).
struct HeldFreeMotion {
  std::weak_ptr<const RobotModel> model;
  Eigen::VectorXd q, qdot;
  double horizon = 0.0;
  std::weak_ptr<const FreeMotionTable> table;
};
std::mutex& heldMutex() {
  static std::mutex m;
  return m;
}
std::vector<HeldFreeMotion>& held() {
  static std::vector<HeldFreeMotion> all;
  return all;
}

bool sameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<size_t>(a.size()) * sizeof(double)) == 0;
}

std::shared_ptr<const FreeMotionTable> heldFreeMotion(const ReferenceParams& p) {
  const std::lock_guard<std::mutex> lock(heldMutex());
  std::vector<HeldFreeMotion>& all = held();
  all.erase(std::remove_if(all.begin(), all.end(),
                           [](const HeldFreeMotion& h) { return h.table.expired() || h.model.expired(); }),
            all.end());
  for (const HeldFreeMotion& h : all)
    if (h.model.lock() == p.model && std::memcmp(&h.horizon, &p.horizon, sizeof(double)) == 0 &&
        sameBits(h.q, p.initial_q) && sameBits(h.qdot, p.initial_qdot))
      if (std::shared_ptr<const FreeMotionTable> table = h.table.lock()) return table;
  return nullptr;
}

void holdFreeMotion(const ReferenceParams& p, const std::shared_ptr<const FreeMotionTable>& table) {
  const std::lock_guard<std::mutex> lock(heldMutex());
  held().push_back({p.model, p.initial_q, p.initial_qdot, p.horizon, table});
}
}  // namespace

Reference::Reference(ReferenceParams params) : params_(std::move(params)) {
  if (params_.type == ReferenceType::kFreeMotion) {
    integrateFreeMotion();
    return;
  }
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

void Reference::integrateFreeMotion() {
  if (!params_.model) throw std::invalid_argument("reference: free_motion needs the robot's model");
  const int n = params_.model->dof();
  if (params_.initial_q.size() != n || params_.initial_qdot.size() != n)
    throw std::invalid_argument("reference: free_motion initial_q and initial_qdot need " +
                                std::to_string(n) + " entries");
  if (!params_.initial_q.allFinite() || !params_.initial_qdot.allFinite() || !(params_.horizon > 0.0))
    throw std::invalid_argument("reference: free_motion needs a finite initial state and a positive horizon");
  if ((free_ = heldFreeMotion(params_))) return;  // integrated already, and still held
  const auto table = std::make_shared<FreeMotionTable>();
  free_ = table;  // the refinement below reads the nodes through evaluate()
  std::vector<Eigen::VectorXd>& nodes = table->nodes;
  std::vector<std::array<double, 3>>& bounds = table->bounds;
  Eigen::VectorXd x(2 * n);
  x << params_.initial_q, params_.initial_qdot;
  const long steps = static_cast<long>(std::ceil(params_.horizon / kFreeStep)) + 1;
  nodes.reserve(static_cast<size_t>(steps) + 1);
  bounds.assign(n, {0.0, 0.0, 0.0});
  auto f = [this, n](const Eigen::VectorXd& s) {
    Eigen::VectorXd d(2 * n);
    d << s.tail(n), params_.model->acceleration(s.head(n), s.tail(n), Eigen::VectorXd::Zero(n));
    return d;
  };
  std::vector<std::array<long, 3>> argmax(static_cast<size_t>(n), {0, 0, 0});
  for (long k = 0; k <= steps; ++k) {
    nodes.push_back(x);
    const Eigen::VectorXd d = f(x);
    for (int i = 0; i < n; ++i) {
      const double values[3] = {std::abs(x(i)), std::abs(x(n + i)), std::abs(d(n + i))};
      for (int order = 0; order < 3; ++order) {
        if (values[order] <= bounds[i][order]) continue;
        bounds[i][order] = values[order];
        argmax[i][order] = k;
      }
    }
    const Eigen::VectorXd k1 = d, k2 = f(x + kFreeStep / 2 * k1), k3 = f(x + kFreeStep / 2 * k2),
                          k4 = f(x + kFreeStep * k3);
    x += kFreeStep / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  // Local maximisation between the nodes around each sampled maximum (golden
  // section on the RK4 interpolant): the peak of a derivative need not fall on a node.
  const double last = static_cast<double>(nodes.size() - 1) * kFreeStep;
  for (int i = 0; i < n; ++i) {
    for (int order = 0; order < 3; ++order) {
      const double centre = static_cast<double>(argmax[i][order]) * kFreeStep;
      auto value = [&](double t) { return std::abs(jointDerivative(i, order, t)); };
      double lo = std::max(0.0, centre - kFreeStep), hi = std::min(last, centre + kFreeStep);
      const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
      double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo), f1 = value(x1), f2 = value(x2);
      for (int it = 0; it < 40; ++it) {
        if (f1 > f2) {
          hi = x2, x2 = x1, f2 = f1, x1 = hi - ratio * (hi - lo), f1 = value(x1);
        } else {
          lo = x1, x1 = x2, f1 = f2, x2 = lo + ratio * (hi - lo), f2 = value(x2);
        }
      }
      bounds[i][order] = std::max({bounds[i][order], f1, f2});
    }
  }
  holdFreeMotion(params_, table);
}

Eigen::VectorXd Reference::freeState(double t) const {
  const std::vector<Eigen::VectorXd>& nodes = free_->nodes;
  const double last = static_cast<double>(nodes.size() - 1) * kFreeStep;
  if (!(t >= 0.0) || t > last)
    throw std::invalid_argument("reference: free_motion was integrated over [0, " + std::to_string(last) +
                                "] s, asked for t = " + std::to_string(t));
  // The last state this thread computed, by table and instant: a loop's
  // metrics and controller ask for the same instant one after the other (an
  // RK4 step of the forward dynamics each), and the second gets the first's.
  struct Memo {
    uint64_t table = 0;
    double t = 0.0;
    Eigen::VectorXd x;
  };
  thread_local Memo memo;
  if (memo.table == free_->id && std::memcmp(&memo.t, &t, sizeof t) == 0) return memo.x;
  const size_t i = std::min(nodes.size() - 1, static_cast<size_t>(t / kFreeStep));
  const double h = t - static_cast<double>(i) * kFreeStep;
  const Eigen::VectorXd& x = nodes[i];
  if (h <= 0.0) return x;
  const int n = params_.model->dof();
  auto f = [this, n](const Eigen::VectorXd& s) {
    Eigen::VectorXd d(2 * n);
    d << s.tail(n), params_.model->acceleration(s.head(n), s.tail(n), Eigen::VectorXd::Zero(n));
    return d;
  };
  const Eigen::VectorXd k1 = f(x), k2 = f(x + h / 2 * k1), k3 = f(x + h / 2 * k2), k4 = f(x + h * k3);
  Eigen::VectorXd state = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  memo.table = 0;  // until it holds this state whole
  memo.x = state;
  memo.table = free_->id;
  memo.t = t;
  return state;
}

double Reference::jointDerivative(int joint, int order, double t) const {
  if (order < 0 || order > 4) throw std::invalid_argument("reference: derivative order must be 0..4");
  if (params_.type == ReferenceType::kFreeMotion) {
    if (order > 2) throw std::invalid_argument("reference: free_motion provides derivatives up to the 2nd");
    const ReferenceSample s = evaluate(t, order);
    return s.derivative[order](joint);
  }
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
  if (params_.type == ReferenceType::kFreeMotion) {
    if (max_order > 2)
      throw std::invalid_argument("reference: free_motion provides derivatives up to the 2nd");
    const int n = dof();
    const Eigen::VectorXd x = freeState(t);
    s.derivative[0] = x.head(n);
    if (max_order >= 1) s.derivative[1] = x.tail(n);
    if (max_order >= 2)
      s.derivative[2] = params_.model->acceleration(x.head(n), x.tail(n), Eigen::VectorXd::Zero(n));
    return s;
  }
  for (int k = 0; k <= max_order; ++k) {
    s.derivative[k].resize(dof());
    for (int i = 0; i < dof(); ++i) s.derivative[k](i) = jointDerivative(i, k, t);
  }
  return s;
}

double Reference::jointBound(int joint, int order) const {
  if (params_.type == ReferenceType::kFreeMotion) {
    if (order > 2) throw std::invalid_argument("reference: free_motion provides derivatives up to the 2nd");
    return 1.02 * free_->bounds[joint][order];  // sampled at every 1e-4 s node, refined between nodes
  }
  const double b = params_.offset(joint), c = params_.amplitude(joint);
  const double w = params_.frequency(joint);
  const double stationary = (order == 0 ? std::abs(b) : 0.0) + std::abs(c) * std::pow(w, order);
  if (params_.type == ReferenceType::kSine) return stationary;

  const double alpha = params_.alpha(joint);
  const double settle = std::cbrt(std::log(1e12) / alpha);  // exp(-alpha t^3) < 1e-12 after it
  const double period = w > 0.0 ? 2.0 * M_PI / w : settle;
  const double horizon = settle + period;
  // Resolve both the transient (time scale alpha^-1/3) and the oscillation,
  // in at most kMaxBoundSamples samples: a slow oscillation with a fast
  // start-up (w = 1e-6, alpha = 1e6) would otherwise ask for 1e13.
  constexpr double kMaxBoundSamples = 4e6;
  const double step =
      std::max(std::min(period, std::cbrt(1.0 / alpha)) / 20000.0, horizon / kMaxBoundSamples);
  double sampled = 0.0;
  for (double t = 0.0; t <= horizon; t += step)
    sampled = std::max(sampled, std::abs(jointDerivative(joint, order, t)));
  return 1.02 * std::max(sampled, stationary);
}

}  // namespace lagrange::model
