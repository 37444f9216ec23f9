#pragma once
/// @file
/// The constants of Assumption 1 and eq. (bndonqd) that the gain conditions use.

#include "model/planar_chain.hpp"
#include "model/reference.hpp"

namespace lagrange::model {

/// k_c with ||C(q, y)|| <= k_c ||y|| for all q, y (Assumption 1.2, induced 2-norm).
///
/// Method: C(q, y) = [C_1(q) ... C_n(q)] (y (x) I), and ||y (x) I|| = ||y||, so
/// for each q the spectral norm of the block row [C_1(q) ... C_n(q)] bounds
/// ||C(q, y)|| / ||y|| exactly (no sampling in y). C depends on q only through
/// the relative angles q_2..q_n and is 2 pi-periodic in each: the supremum over
/// q is sampled, on a uniform grid of 7200 points for n = 2 and on 20000
/// seeded uniform random points of [0, 2 pi)^(n-1) for n > 2, and multiplied by
/// a safety factor of 1.05 for the sampling. For n = 1, C = 0 and k_c = 0.
double coriolisBound(const PlanarChain& chain);

/// Per-q quantity maximised by coriolisBound: ||[C_1(q) ... C_n(q)]||_2.
double coriolisGain(const PlanarChain& chain, const Eigen::VectorXd& q);

/// k_delta of eq. (bndonqd): an upper bound of max over k = 0,1,2 of
/// sup_t ||d^k q_d/dt^k||, from the per-joint bounds of Reference::jointBound
/// (||v|| <= sqrt(sum_i sup |v_i|^2)).
double referenceBound(const Reference& reference);

}  // namespace lagrange::model
