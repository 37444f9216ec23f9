#include "lagrange/sdk/scenario.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "lagrange/sdk/external_controller.hpp"

namespace lagrange::sdk {

nlohmann::json scenario() {
  const char* path = std::getenv("LAGRANGE_CONFIG_JSON");
  if (path == nullptr || *path == '\0')
    throw ContractError(
        "LAGRANGE_CONFIG_JSON is not set: the resolved scenario is handed over by `lagrange run` and "
        "`lagrange replay` (controller.type: external)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ContractError(std::string("cannot read the scenario ") + path + " (LAGRANGE_CONFIG_JSON)");
  std::ostringstream text;
  text << in.rdbuf();
  nlohmann::json s = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (s.is_discarded() || !s.is_object())
    throw ContractError(std::string("the scenario ") + path +
                        " (LAGRANGE_CONFIG_JSON) is not a JSON object; expected the config.resolved.json "
                        "lagrange writes");
  return s;
}

}  // namespace lagrange::sdk
