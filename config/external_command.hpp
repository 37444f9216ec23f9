#pragma once
/// @file
/// The command line of a program from outside the project that takes a
/// process's place -- `controller.command` (controller.type external) or
/// `plant.command` (plant.type external) -- and the folder it starts in,
/// checked before anything starts (docs/external_programs.md).

#include <string>
#include <vector>

#include "config/yaml_reader.hpp"

namespace lagrange::config {

struct ExternalCommand {
  /// argv, no shell; argv[0] absolute when given as a path.
  std::vector<std::string> command;
  std::string working_directory;  ///< absolute
};

/// Reads `command` and `working_directory` from `section` (the controller's
/// or the plant's): a relative path is taken from base_dir (the scenario
/// file's folder); a program or folder that does not exist is refused, naming
/// `role` ("controller", "plant") -- unless `check_programs` is false: a
/// log's scenario names programs of the host and time it ran, which its
/// readers (replay, report, export, view) never run.
ExternalCommand readExternalCommand(MapReader& section, const std::string& base_dir, const std::string& role,
                                    bool check_programs = true);

}  // namespace lagrange::config
