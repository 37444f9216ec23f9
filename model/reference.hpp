#pragma once
/// @file
/// Reference trajectories q_d(t) with analytic time derivatives up to the 4th.
///
/// Per joint i (all parameters per joint):
///   sine:         q_d,i(t) = b_i + c_i sin(w_i t + p_i)
///   smooth_sine:  q_d,i(t) = (1 - exp(-alpha_i t^3)) (b_i + c_i sin(w_i t + p_i))
/// The smooth-start sinusoid is the reference of Kelly, Santibanez and Loria's
/// book: it starts at rest at zero, with zero derivatives up to the 2nd.
///   free_motion:  q_d solves D(q_d)q_d'' + C(q_d,q_d')q_d' + g(q_d) = 0 from a
///                 given state (Assumption 2). Integrated once by RK4 with a
///                 1e-4 s step over [0, horizon]; between nodes the state is
///                 one further RK4 step from the node before t, and q_d'' comes
///                 from the model. Derivatives up to the 2nd only. The
///                 integration is shared, read-only, by every Reference of the
///                 same model object, initial state and horizon alive at once
///                 (copies, and the controller's and the metrics' of one
///                 scenario): it is the same computation, done once.

#include <Eigen/Dense>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/robot_model.hpp"
#include "util/enum_names.hpp"

namespace lagrange::model {

enum class ReferenceType { kSine, kSmoothSine, kFreeMotion };

/// Per-joint parameters of a reference.
struct ReferenceParams {
  ReferenceType type = ReferenceType::kSmoothSine;
  Eigen::VectorXd offset;     ///< b [rad]
  Eigen::VectorXd amplitude;  ///< c [rad]
  Eigen::VectorXd frequency;  ///< w [rad/s]
  Eigen::VectorXd phase;      ///< p [rad]
  Eigen::VectorXd alpha;      ///< smooth-start rate [1/s^3]; smooth_sine only

  // free_motion: the unforced motion D(q)q'' + C(q,q')q' + g(q) = 0 of the
  // arm `model` from (initial_q, initial_qdot) -- Assumption 2 of the paper.
  Eigen::VectorXd initial_q, initial_qdot;  ///< [rad], [rad/s]
  RobotModelPtr model;                      ///< the arm whose free motion it is
  double horizon = 0.0;                     ///< integrated over [0, horizon] [s]
};

/// q_d and its derivatives at one instant; derivative[k] is d^k q_d / dt^k.
struct ReferenceSample {
  std::array<Eigen::VectorXd, 5> derivative;
  const Eigen::VectorXd& q() const { return derivative[0]; }
  const Eigen::VectorXd& qd() const { return derivative[1]; }
  const Eigen::VectorXd& qdd() const { return derivative[2]; }
};

struct FreeMotionTable;  ///< a free_motion reference's integration (reference.cpp)

class Reference {
 public:
  /// @throws std::invalid_argument if sizes differ, a value is not finite,
  ///         a frequency is negative, or (smooth_sine) an alpha is not positive.
  explicit Reference(ReferenceParams params);

  int dof() const {
    return static_cast<int>(params_.type == ReferenceType::kFreeMotion ? params_.initial_q.size()
                                                                       : params_.offset.size());
  }
  const ReferenceParams& params() const { return params_; }

  /// q_d and its derivatives up to max_order (0..4) at t; higher orders are
  /// left empty (the Theorem 4 controller needs 2, the chains up to m + 2).
  ReferenceSample evaluate(double t, int max_order = 4) const;

  /// d^order q_d,joint / dt^order at t, order 0..4.
  double jointDerivative(int joint, int order, double t) const;

  /// Upper bound of sup_{t >= 0} |d^order q_d,joint / dt^order|, order 0..4.
  /// sine: closed form (|b| + |c|, |c| w^order). smooth_sine: the larger of the
  /// stationary closed form and a sampled supremum over the start-up transient
  /// (t in [0, T_s + 2 pi / w], T_s where exp(-alpha t^3) < 1e-12, 20000
  /// samples per period at least), times a safety factor of 1.02 for sampling.
  /// free_motion (orders 0..2): the largest value at the integration nodes
  /// (every 1e-4 s over the horizon), refined by a golden-section search
  /// between the nodes around it, times 1.02. Only sine's is a proven bound;
  /// the others are estimates (boundIsExact).
  double jointBound(int joint, int order) const;

  /// Whether jointBound is a closed form (sine) rather than a sampled estimate.
  bool boundIsExact() const { return params_.type == ReferenceType::kSine; }

 private:
  void integrateFreeMotion();
  /// [q; q'] of the free motion at t.
  Eigen::VectorXd freeState(double t) const;

  ReferenceParams params_;
  // free_motion only: nodes every kFreeStep seconds, and sampled bounds,
  // immutable once integrated and shared (reference.cpp).
  std::shared_ptr<const FreeMotionTable> free_;
};

/// The spelling in scenario files (reference.type).
inline constexpr util::EnumName<ReferenceType> kReferenceTypeNames[] = {
    {ReferenceType::kSine, "sine"},
    {ReferenceType::kSmoothSine, "smooth_sine"},
    {ReferenceType::kFreeMotion, "free_motion"}};
inline const char* toString(ReferenceType type) { return util::nameOf(kReferenceTypeNames, type); }

}  // namespace lagrange::model
