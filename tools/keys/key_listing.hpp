#pragma once
/// @file
/// The terminal form of the key reference (`lagrange keys`).

#include <string>
#include <vector>

namespace lagrange::tools {

/// The keys in `sections` (a key is in "controller" when it is "controller"
/// or starts with "controller." or "controller["; all keys when empty; a key
/// described in another key's row, robot.links[i].mass, gives that row), each
/// as
///   plant.physics_step  (number > 0; default `1.0e-4`)
///       ODE step [s]; ... Range: from 1e-7 to 1 s (...).
/// with the meaning wrapped at `width` columns.
/// @throws BadInput naming a section no key is in, and the top-level keys.
std::string keyListing(const std::vector<std::string>& sections, int width = 100);

}  // namespace lagrange::tools
