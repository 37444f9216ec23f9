#pragma once
/// @file
/// A plant the controller does not know: a payload at the last link and
/// seeded relative errors in every link's mass, inertia and centre of mass.
/// The controllers keep the nominal arm (Scenario::robotModel()); the plant
/// builds its bodies from what these functions return. Pure.
///
/// Model error, per link i, with u uniform in [-1, 1] drawn from `seed`
/// (SplitMix64; three draws per link, in the order mass, inertia, com):
///   mass_i    -> mass_i (1 + mass u)
///   inertia_i -> inertia_i (1 + inertia u')      (the whole tensor, so it stays one)
///   com_i     -> joint_i + (1 + com u'') (com_i - joint_i)   (its distance from the joint)
/// The sizes are below 1, so every mass and inertia stays positive.
/// Payload: a point mass at a point of the last link (the planar chain: a
/// distance along it from its joint; a URDF arm: a point in tip_link's frame),
/// merged into the last body by the parallel-axis theorem.

#include <Eigen/Dense>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/planar_chain.hpp"
#include "model/urdf_arm.hpp"

namespace lagrange::model {

struct Payload {
  double mass = 0.0;  ///< [kg], >= 0
  Eigen::Vector3d com =
      Eigen::Vector3d::Zero();  ///< chain: com.x() along the last link [m]; URDF: in tip_link's frame
};

struct ModelError {
  double mass = 0.0, inertia = 0.0, com = 0.0;  ///< relative sizes, in [0, 1)
  std::uint64_t seed = 1;
};

/// One link as the controller knows it and as the plant has it.
struct LinkChange {
  std::string link;
  double nominal_mass = 0.0, mass = 0.0;
  double inertia_scale = 1.0;  ///< the plant's inertia tensor / the nominal's (payload not included)
  Eigen::Vector3d nominal_com = Eigen::Vector3d::Zero(), com = Eigen::Vector3d::Zero();  ///< [m]
};

/// What the plant is: the chain (or URDF bodies) after model error and payload.
struct PerturbedChain {
  ChainParams params;
  std::vector<LinkChange> changes;
};
struct PerturbedBodies {
  std::vector<UrdfBody> bodies;
  std::vector<LinkChange> changes;
};

/// @throws std::invalid_argument on a negative payload mass or a size outside [0, 1).
PerturbedChain perturbedChain(const ChainParams& nominal, const std::optional<Payload>& payload,
                              const std::optional<ModelError>& error);
PerturbedBodies perturbedBodies(const UrdfArm& nominal, const std::optional<Payload>& payload,
                                const std::optional<ModelError>& error);

}  // namespace lagrange::model
