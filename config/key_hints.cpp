/// @file
/// Near misses and guessed keys (config/key_hints.hpp).
#include "config/key_hints.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include "config/key_table.hpp"

namespace lagrange::config {

// Each guess is an unknown key (never one the table has: a test holds them
// apart), named as the key table names it; its text follows "; " in an error
// that has already named the key as unknown.
const std::map<std::string, std::string>& keyGuesses() {
  static const std::string rate =
      "the control rate is plant.publish_rate [Hz]: the controller runs once per position sample";
  static const std::string period =
      "the control period is 1 / plant.publish_rate: give the rate, plant.publish_rate [Hz]";
  static const std::string step =
      "the simulation's step is plant.physics_step [s]; the control period is 1 / plant.publish_rate [Hz]";
  static const std::string length = "the simulated time is duration [s], a top-level key";
  static const std::map<std::string, std::string> table = {
      // The control rate, wherever it is looked for.
      {"rate", rate},
      {"frequency", rate},
      {"control_rate", rate},
      {"sample_rate", rate},
      {"sampling_rate", rate},
      {"publish_rate", rate},
      {"controller.rate", rate},
      {"controller.frequency", rate},
      {"controller.control_rate", rate},
      {"controller.sample_rate", rate},
      {"controller.sampling_rate", rate},
      {"controller.publish_rate", rate},
      {"plant.rate", rate},
      {"plant.frequency", rate},
      {"plant.control_rate", rate},
      {"plant.sample_rate", rate},
      {"plant.sampling_rate", rate},
      // Its period.
      {"period", period},
      {"sample_time", period},
      {"controller.period", period},
      {"controller.dt", period},
      {"controller.sample_time", period},
      {"controller.sampling_period", period},
      {"plant.period", period},
      {"plant.sample_time", period},
      // The physics step, or the period: a bare dt may mean either.
      {"dt", step},
      {"physics_step", step},
      {"plant.dt", step},
      {"plant.step", step},
      {"plant.time_step", step},
      {"plant.timestep", step},
      // The run's length.
      {"time", length},
      {"sim_time", length},
      {"end_time", length},
      {"t_end", length},
      {"t_final", length},
      {"run",
       "there is no run section: the run's length is duration [s] and its wiring mode, both top-level keys"},
  };
  return table;
}

namespace {

// The key as compared: lower case, without `_` and `-` ("Publish_Rate" ->
// "publishrate").
std::string folded(const std::string& key) {
  std::string out;
  for (const char c : key)
    if (c != '_' && c != '-') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Edits (insert, delete, replace, swap two neighbours) from a to b.
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// How many edits still make a near miss of a known key of this length
// (folded): none for one or two letters, where one edit is another word.
size_t editsAllowed(size_t length) { return length <= 2 ? 0 : length <= 5 ? 1 : 2; }

}  // namespace

std::vector<std::string> nearMisses(const std::string& unknown, const std::set<std::string>& known) {
  // A key far longer than any known one (a hostile file's) is no misspelling.
  if (unknown.size() > 64) return {};
  const std::string u = folded(unknown);
  size_t best = SIZE_MAX;
  std::vector<std::string> out;
  for (const std::string& k : known) {
    if (k == unknown) continue;
    const std::string f = folded(k);
    // Lengths further apart than the edits allowed: no near miss, and no
    // table to fill (a hostile map of many keys costs a comparison each).
    const size_t apart = u.size() > f.size() ? u.size() - f.size() : f.size() - u.size();
    if (apart > editsAllowed(f.size())) continue;
    const size_t d = editDistance(u, f);
    if (d > editsAllowed(f.size()) || d > best) continue;
    if (d < best) out.clear();
    best = d;
    out.push_back(k);
  }
  return out;
}

std::string guessedKeyMeaning(const std::string& table_key) {
  const auto it = keyGuesses().find(table_key);
  return it == keyGuesses().end() ? "" : it->second;
}

std::string unknownKeyHint(const std::string& key, const std::string& table_key,
                           const std::set<std::string>& known) {
  if (const std::string meaning = guessedKeyMeaning(table_key); !meaning.empty()) return "; " + meaning;
  const std::vector<std::string> near = nearMisses(key, known);
  if (near.empty()) return "";
  std::string names;
  for (size_t i = 0; i < near.size(); ++i)
    names += (i == 0 ? "" : i + 1 == near.size() ? " or " : ", ") + near[i];
  return "; did you mean " + names + "?";
}

bool isTableKey(const std::string& table_key) {
  for (const KeyInfo& k : keyTable())
    if (k.key == table_key || k.key.compare(0, table_key.size() + 1, table_key + ".") == 0 ||
        k.key.compare(0, table_key.size() + 1, table_key + "[") == 0)
      return true;
  return false;
}

}  // namespace lagrange::config
