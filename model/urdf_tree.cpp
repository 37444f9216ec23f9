#include "model/urdf_tree.hpp"

#include <map>
#include <set>
#include <vector>

#include "util/error.hpp"

namespace lagrange::model {

void checkUrdfTree(const urdf::ModelInterface& robot, const std::string& where) {
  if (robot.joints_.size() > static_cast<std::size_t>(kMaxUrdfJoints))
    throw BadInput(where + ": " + std::to_string(robot.joints_.size()) + " joints; at most " +
                   std::to_string(kMaxUrdfJoints) + " are allowed");
  std::map<std::string, std::string> parent_joint;              // link -> the joint it is the child of
  std::map<std::string, std::vector<std::string>> child_links;  // link -> the links of its child joints
  for (const auto& [name, joint] : robot.joints_) {
    for (const std::string* link : {&joint->parent_link_name, &joint->child_link_name})
      if (robot.links_.count(*link) == 0)
        throw BadInput(where + ": joint '" + name + "' names link '" + *link +
                       "', which the document does not define; expected a tree of links and joints");
    const auto [other, first] = parent_joint.emplace(joint->child_link_name, name);
    if (!first)
      throw BadInput(where + ": link '" + joint->child_link_name + "' is the child of two joints ('" +
                     other->second + "' and '" + name +
                     "'); expected a tree (each link the child of at most one joint, no loops)");
    child_links[joint->parent_link_name].push_back(joint->child_link_name);
  }
  const urdf::LinkConstSharedPtr root = robot.getRoot();
  if (!root || parent_joint.count(root->name) > 0)
    throw BadInput(where + ": no root link (every link is the child of a joint); expected a tree");
  // Every link reachable from the root: what is not hangs in a loop of its own.
  std::set<std::string> reached{root->name};
  std::vector<std::string> todo{root->name};
  while (!todo.empty()) {
    const std::string link = todo.back();
    todo.pop_back();
    for (const std::string& child : child_links[link])
      if (reached.insert(child).second) todo.push_back(child);
  }
  for (const auto& [name, link] : robot.links_)
    if (reached.count(name) == 0)
      throw BadInput(where + ": link '" + name + "' cannot be reached from the root link '" + root->name +
                     "' (its joints form a loop); expected a tree");
}

}  // namespace lagrange::model
