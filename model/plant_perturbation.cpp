#include "model/plant_perturbation.hpp"

#include <cmath>
#include <stdexcept>

#include "util/splitmix.hpp"

namespace lagrange::model {

namespace {

using Draws = util::SplitMix64Stream;

void validate(const std::optional<Payload>& payload, const std::optional<ModelError>& error) {
  if (payload && !(payload->mass >= 0.0 && std::isfinite(payload->mass) && payload->com.allFinite()))
    throw std::invalid_argument("payload: expected a finite mass >= 0 and a finite point");
  if (error)
    for (const double size : {error->mass, error->inertia, error->com})
      if (!(size >= 0.0 && size < 1.0))
        throw std::invalid_argument("model error: expected relative sizes in [0, 1), got " +
                                    std::to_string(size));
}

// The relative factors of one link: mass, inertia, com distance.
struct Factors {
  double mass = 1.0, inertia = 1.0, com = 1.0;
};
Factors draw(Draws* draws, const std::optional<ModelError>& error) {
  if (!error) return {};
  const double um = draws->symmetric(), ui = draws->symmetric(), uc = draws->symmetric();
  return {1.0 + error->mass * um, 1.0 + error->inertia * ui, 1.0 + error->com * uc};
}

Eigen::Matrix3d pointInertia(double mass, const Eigen::Vector3d& d) {
  return mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

}  // namespace

PerturbedChain perturbedChain(const ChainParams& nominal, const std::optional<Payload>& payload,
                              const std::optional<ModelError>& error) {
  validate(payload, error);
  PerturbedChain out{nominal, {}};
  Draws draws(error ? error->seed : 0);
  for (size_t i = 0; i < out.params.links.size(); ++i) {
    LinkParams& link = out.params.links[i];
    const Factors f = draw(&draws, error);
    LinkChange change{"link " + std::to_string(i + 1),
                      link.mass,
                      link.mass * f.mass,
                      f.inertia,
                      Eigen::Vector3d(link.com, 0, 0),
                      Eigen::Vector3d(link.com * f.com, 0, 0)};
    link.mass = change.mass;
    link.inertia *= f.inertia;
    link.com = change.com.x();
    out.changes.push_back(change);
  }
  if (payload && payload->mass > 0.0) {
    LinkParams& last = out.params.links.back();
    const double m = last.mass + payload->mass, r = payload->com.x();
    const double com = (last.mass * last.com + payload->mass * r) / m;
    last.inertia += last.mass * (last.com - com) * (last.com - com) + payload->mass * (r - com) * (r - com);
    last.mass = m;
    last.com = com;
  }
  return out;
}

PerturbedBodies perturbedBodies(const UrdfArm& nominal, const std::optional<Payload>& payload,
                                const std::optional<ModelError>& error) {
  validate(payload, error);
  PerturbedBodies out{nominal.bodies(), {}};
  Draws draws(error ? error->seed : 0);
  for (UrdfBody& body : out.bodies) {
    const Factors f = draw(&draws, error);
    LinkChange change{body.link, body.mass, body.mass * f.mass,
                      f.inertia, body.com,  body.joint_anchor + f.com * (body.com - body.joint_anchor)};
    body.mass = change.mass;
    body.inertia *= f.inertia;
    body.com = change.com;
    out.changes.push_back(change);
  }
  if (payload && payload->mass > 0.0) {
    // The bodies are at q = 0, in the base frame: so is the tip's frame.
    const Eigen::Vector3d at = nominal.tipFrame(Eigen::VectorXd::Zero(nominal.dof())) * payload->com;
    UrdfBody& last = out.bodies.back();
    const double m = last.mass + payload->mass;
    const Eigen::Vector3d com = (last.mass * last.com + payload->mass * at) / m;
    last.inertia += pointInertia(last.mass, last.com - com) + pointInertia(payload->mass, at - com);
    last.mass = m;
    last.com = com;
  }
  return out;
}

}  // namespace lagrange::model
