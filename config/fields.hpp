#pragma once
/// @file
/// A section of the scenario file read and written field by field: each
/// field names its key and how it is read (with its constraint) and written,
/// so the reader, the writer of config.resolved.yaml and the list of known
/// keys come from one description (a test holds these keys to the key table,
/// config/key_table.hpp, which documents them and holds their ranges).
///
///   const Fields<MetricsConfig> kMetricsFields = {
///       positive("tolerance", &MetricsConfig::tolerance), ...};
///   readFields(root.map("metrics"), s.metrics, kMetricsFields);
///   writeFields(out, s.metrics, kMetricsFields);
///
/// Fields that depend on other sections (joint counts, the controller's
/// type) keep their hand-written readers, which take their known keys from
/// the key table (keysUnder).

#include <yaml-cpp/yaml.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "config/yaml_reader.hpp"
#include "util/enum_names.hpp"

namespace lagrange::config {

template <class T>
struct Field {
  std::string key;
  std::function<void(MapReader&, T&)> read;             ///< keeps the default when the key is absent
  std::function<void(YAML::Emitter&, const T&)> write;  ///< emits "key: value"
};
template <class T>
using Fields = std::vector<Field<T>>;

template <class T>
std::set<std::string> keysOf(const Fields<T>& fields) {
  std::set<std::string> keys;
  for (const Field<T>& f : fields) keys.insert(f.key);
  return keys;
}

/// Reads every field present, then rejects any key no field describes.
template <class T>
void readFields(MapReader map, T& value, const Fields<T>& fields) {
  for (const Field<T>& f : fields) f.read(map, value);
  map.finish(keysOf(fields));
}

template <class T>
void writeFields(YAML::Emitter& out, const T& value, const Fields<T>& fields) {
  for (const Field<T>& f : fields) f.write(out, value);
}

namespace field {

template <class T, class V>
std::function<void(YAML::Emitter&, const T&)> plainWriter(const std::string& key, V T::*member) {
  return
      [key, member](YAML::Emitter& out, const T& t) { out << YAML::Key << key << YAML::Value << t.*member; };
}

/// A number > 0.
template <class T>
Field<T> positive(const std::string& key, double T::*member) {
  return {key, [key, member](MapReader& m, T& t) { t.*member = m.positive(key, t.*member); },
          plainWriter(key, member)};
}

/// A whole number in [min, max]; `expected` says so in the error.
template <class T>
Field<T> integer(const std::string& key, int T::*member, int min, int max, const std::string& expected) {
  return {key,
          [=](MapReader& m, T& t) {
            t.*member = m.integer(key, t.*member);
            if (t.*member < min || t.*member > max) m.fail(key, expected);
          },
          plainWriter(key, member)};
}

/// One of an enum's names; `what` names the kind of choice in the error.
template <class T, class E, std::size_t N>
Field<T> choice(const std::string& key, E T::*member, const util::EnumName<E> (&names)[N],
                const std::string& what) {
  return {
      key,
      [key, member, &names, what](MapReader& m, T& t) { t.*member = m.choice(key, names, what, t.*member); },
      [key, member, &names](YAML::Emitter& out, const T& t) {
        out << YAML::Key << key << YAML::Value << util::nameOf(names, t.*member);
      }};
}

}  // namespace field
}  // namespace lagrange::config
