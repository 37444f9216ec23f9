// A free_motion reference's integration is shared by the References of the
// same model object, initial state and horizon alive at once, and the last
// state a thread computed is reused for the same instant (model/reference.hpp;
// #55: the sampled-data check built it in every simulation, twice). Either
// must give the bits a Reference built alone gives, and never another
// motion's.
#include <gtest/gtest.h>

#include <cstring>
#include <thread>
#include <vector>

#include "model/planar_chain.hpp"
#include "model/reference.hpp"

namespace lagrange::model {
namespace {

ReferenceParams freeMotion(const RobotModelPtr& arm, double q0) {
  ReferenceParams p;
  p.type = ReferenceType::kFreeMotion;
  p.initial_q = Eigen::Vector2d(q0, 0.3);
  p.initial_qdot = Eigen::Vector2d(0.0, 1.0);
  p.model = arm;
  p.horizon = 2.0;
  return p;
}

// q, q', q'' at instants on and between the integration nodes, and the bounds, as doubles.
std::vector<double> values(const Reference& r) {
  std::vector<double> out;
  for (double t : {0.0, 0.00013, 0.5, 0.5, 1.23456, 0.00013, 1.9999}) {
    const ReferenceSample s = r.evaluate(t, 2);
    for (int k = 0; k < 3; ++k) out.insert(out.end(), s.derivative[k].data(), s.derivative[k].data() + 2);
  }
  for (int joint = 0; joint < 2; ++joint)
    for (int order = 0; order < 3; ++order) out.push_back(r.jointBound(joint, order));
  return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(FreeMotionSharing, HeldCopiesAndRebuildsGiveTheBitsOfOneBuiltAlone) {
  const RobotModelPtr arm = std::make_shared<PlanarChain>(pelicanParams());
  std::vector<double> alone;
  {
    const Reference r(freeMotion(arm, 0.5));
    alone = values(r);
  }  // gone: the next one integrates again
  const Reference held(freeMotion(arm, 0.5));
  const Reference shared(freeMotion(arm, 0.5));  // built while `held` lives
  const Reference copy = shared;
  EXPECT_TRUE(sameBits(values(held), alone));
  EXPECT_TRUE(sameBits(values(shared), alone));
  EXPECT_TRUE(sameBits(values(copy), alone));
}

TEST(FreeMotionSharing, AnotherStateOrArmIsAnotherMotion) {
  const RobotModelPtr arm = std::make_shared<PlanarChain>(pelicanParams());
  const Reference held(freeMotion(arm, 0.5));
  const std::vector<double> mine = values(held);
  // A different initial angle, and the same numbers for another arm object
  // with a heavier link: each its own motion, not the held one's.
  const Reference other_state(freeMotion(arm, 0.6));
  ChainParams heavier = pelicanParams();
  heavier.links[1].mass *= 2.0;
  const Reference other_arm(freeMotion(std::make_shared<PlanarChain>(heavier), 0.5));
  for (const Reference* r : {&other_state, &other_arm}) {
    const std::vector<double> theirs = values(*r);
    EXPECT_FALSE(sameBits(theirs, mine));
    EXPECT_NE(r->evaluate(0.5, 0).q(), held.evaluate(0.5, 0).q());  // the instant memo keeps them apart too
  }
  // An equal arm built anew is another object: its motion is integrated, and equal.
  const Reference same_numbers(freeMotion(std::make_shared<PlanarChain>(pelicanParams()), 0.5));
  EXPECT_TRUE(sameBits(values(same_numbers), mine));
}

TEST(FreeMotionSharing, FourThreadsReadingOneReferenceComputeWhatOneThreadDoes) {
  const RobotModelPtr arm = std::make_shared<PlanarChain>(pelicanParams());
  const Reference r(freeMotion(arm, 0.5));
  std::vector<Eigen::VectorXd> expected;
  for (int k = 0; k < 2000; ++k) expected.push_back(r.evaluate(k * 7.7e-4, 2).qdd());
  std::vector<int> wrong(4, 0);
  std::vector<std::thread> threads;
  for (int w = 0; w < 4; ++w)
    threads.emplace_back([&, w] {
      for (int pass = 0; pass < 3; ++pass)
        for (int k = (w + pass) % 4; k < 2000; k += 1 + w)
          if (r.evaluate(k * 7.7e-4, 2).qdd() != expected[k]) ++wrong[w];
    });
  for (std::thread& t : threads) t.join();
  for (int w = 0; w < 4; ++w) EXPECT_EQ(wrong[w], 0) << "thread " << w;
}

}  // namespace
}  // namespace lagrange::model
