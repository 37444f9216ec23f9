#pragma once
/// @file
/// The constants of Assumption 1 and eq. (bndonqd) that the gain conditions use.

#include <optional>

#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::model {

/// k_c with ||C(q, y)|| <= k_c ||y|| for all q, y (Assumption 1.2, induced
/// 2-norm), proven from the model's closed form of C; none when the model has
/// no closed form (RobotModel::coriolisTerms), and then coriolisLargestFound
/// is all there is: an estimate from below, which a report must call one.
///
/// C(q, y) = [C_1(q) ... C_n(q)] (y (x) I) and ||y (x) I|| = ||y||, so
/// ||C(q, y)|| / ||y|| <= ||[C_1(q) ... C_n(q)]||_2 =: G(q) for every y. By
/// the closed form (RobotModel::coriolisTerms; the planar chain's), [C_1 ... C_n](q) =
/// sum_p s_p P_p over the N link pairs p = (a, b), s_p = sin(phi_a - phi_b),
/// P_p constant; so G(q) <= sum_p ||P_p|| (triangle inequality, |s_p| <= 1)
/// and G(q) <= ||[P_1 ... P_N]|| ||s|| <= sqrt(N) ||[P_1 ... P_N]||. k_c is
/// the smaller of the two. For n = 2 (one pair, sin q_2 reaching 1) it is the
/// supremum exactly; for longer chains it can exceed the supremum
/// (coriolisLargestFound gives a lower bound of it). For n = 1, C = 0.
std::optional<double> coriolisBound(const RobotModel& model);

/// The largest G(q) found: a grid of 7200 points for n = 2, else 20000 seeded
/// random points of the torus [0, 2 pi)^(n-1) (q_1 is left at 0: D, and so G,
/// does not depend on the first joint's angle of a fixed-base arm), each of the 4 best then refined by a
/// compass search. A lower bound of sup G, reported beside coriolisBound to show how tight it is.
/// Past 8 joints the samples shrink as (8/n)^4 (at least 100) and one start is
/// refined, by as many compass steps: the search's cost stays that of 8 joints.
double coriolisLargestFound(const RobotModel& model);

/// G(q) = ||[C_1(q) ... C_n(q)]||_2.
double coriolisGain(const RobotModel& model, const Eigen::VectorXd& q);

/// k_delta of eq. (bndonqd): an upper bound of max over k = 0,1,2 of
/// sup_t ||d^k q_d/dt^k||, from the per-joint bounds of Reference::jointBound
/// (||v|| <= sqrt(sum_i sup |v_i|^2)).
double referenceBound(const Reference& reference);

}  // namespace lagrange::model
