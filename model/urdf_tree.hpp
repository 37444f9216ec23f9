#pragma once
/// @file
/// urdfdom accepts documents whose joints do not form a tree: a link that is
/// the child of two joints keeps the last parent, a loop hanging below the
/// root parses, and walking such a "tree" (up from the tip, down a subtree)
/// never ends. checkUrdfTree refuses them before anything walks the tree.

#include <urdf_model/model.h>

#include <string>

namespace lagrange::model {

/// Joints (of any type) a URDF document may have: the largest real robot
/// descriptions (humanoids with hands) have a few hundred.
inline constexpr int kMaxUrdfJoints = 1000;

/// @throws Error naming `where` and what is wrong: more than kMaxUrdfJoints
/// joints, a joint naming a link that does not exist, a link that is the
/// child of two joints, links that cannot be reached from the root (a loop).
void checkUrdfTree(const urdf::ModelInterface& robot, const std::string& where);

}  // namespace lagrange::model
