#pragma once
/// @file
/// A key registered from outside config whose value is a per-joint vector:
/// a controller's parameter (config/controller_params.hpp), a sensor model's
/// (config/sensor_models.hpp).

#include <string>

namespace lagrange::config {

/// A list of n numbers, or one number for every joint.
struct JointVectorKey {
  std::string key;
  bool positive = false;  ///< every entry > 0
  std::string doc;        ///< what it is, with its unit (error messages, docs)
};

}  // namespace lagrange::config
