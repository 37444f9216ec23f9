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

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <optional>
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

/// Reads every field present and leaves the map open: for the top level,
/// whose other keys are sections with readers of their own.
template <class T>
void readFieldsAmongOthers(MapReader& map, T& value, const Fields<T>& fields) {
  for (const Field<T>& f : fields) f.read(map, value);
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

/// Whether a field may be left out (its member's value is then the default).
enum class Presence { kOptional, kRequired };

/// A number > 0.
template <class T>
Field<T> positive(const std::string& key, double T::*member, Presence presence = Presence::kOptional) {
  return {key,
          [key, member, presence](MapReader& m, T& t) {
            t.*member = presence == Presence::kRequired ? m.positive(key) : m.positive(key, t.*member);
          },
          plainWriter(key, member)};
}

/// A whole number >= 0 that seeds random draws.
template <class T>
Field<T> seed(const std::string& key, uint64_t T::*member) {
  return {key,
          [key, member](MapReader& m, T& t) {
            const int value = m.integer(key, static_cast<int>(t.*member));
            if (value < 0) m.fail(key, "expected a whole number >= 0");
            t.*member = static_cast<uint64_t>(value);
          },
          plainWriter(key, member)};
}

/// A string.
template <class T>
Field<T> text(const std::string& key, std::string T::*member, Presence presence = Presence::kOptional) {
  return {key,
          [key, member, presence](MapReader& m, T& t) {
            t.*member = presence == Presence::kRequired ? m.text(key) : m.text(key, t.*member);
          },
          plainWriter(key, member)};
}

/// true or false.
template <class T>
Field<T> boolean(const std::string& key, bool T::*member) {
  return {key, [key, member](MapReader& m, T& t) { t.*member = m.boolean(key, t.*member); },
          plainWriter(key, member)};
}

/// A number > 0 or, left out, none (and then not written either).
template <class T>
Field<T> optionalPositive(const std::string& key, std::optional<double> T::*member) {
  return {key,
          [key, member](MapReader& m, T& t) {
            if (m.has(key)) t.*member = m.positive(key);
          },
          [key, member](YAML::Emitter& out, const T& t) {
            if (t.*member) out << YAML::Key << key << YAML::Value << *(t.*member);
          }};
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

/// A number in [0, 1].
template <class T>
Field<T> probability(const std::string& key, double T::*member) {
  return {key,
          [key, member](MapReader& m, T& t) {
            t.*member = m.number(key, t.*member);
            if (t.*member < 0.0 || t.*member > 1.0) m.fail(key, "expected a probability from 0 to 1");
          },
          plainWriter(key, member)};
}

/// A number >= 0; `expected` says so in the error ("expected a time >= 0 [s]").
template <class T>
Field<T> nonNegative(const std::string& key, double T::*member, const std::string& expected,
                     Presence presence = Presence::kOptional) {
  return {key,
          [=](MapReader& m, T& t) {
            t.*member = presence == Presence::kRequired ? m.number(key) : m.number(key, t.*member);
            if (t.*member < 0.0) m.fail(key, expected);
          },
          plainWriter(key, member)};
}

/// A whole number >= min; the error is `expected`, then the number read.
template <class T>
Field<T> wholeAtLeast(const std::string& key, int T::*member, int min, const std::string& expected) {
  return {key,
          [=](MapReader& m, T& t) {
            t.*member = m.integer(key, t.*member);
            if (t.*member < min) m.fail(key, expected + ", got " + std::to_string(t.*member));
          },
          plainWriter(key, member)};
}

/// Emits "key: [v0, v1, ...]" on one line.
inline void writeVector(YAML::Emitter& out, const std::string& key, const Eigen::VectorXd& v) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (Eigen::Index i = 0; i < v.size(); ++i) out << v(i);
  out << YAML::EndSeq;
}

/// Fails through map.fail(key, ...) when a vector just read is out of its
/// domain ("expected numbers >= 0 [rad/s], got -1").
using VectorCheck = std::function<void(MapReader&, const std::string&, const Eigen::VectorXd&)>;

/// How a per-joint vector is read: VectorRule().required().positiveOnly().
struct VectorRule {
  Presence presence = Presence::kOptional;
  bool one_number_for_all = true;  ///< a single number stands for every joint
  bool positive_only = false;
  VectorCheck check;

  VectorRule& required() {
    presence = Presence::kRequired;
    return *this;
  }
  VectorRule& listOnly() {
    one_number_for_all = false;
    return *this;
  }
  VectorRule& positiveOnly() {
    positive_only = true;
    return *this;
  }
  VectorRule& checkedBy(VectorCheck c) {
    check = std::move(c);
    return *this;
  }
};

/// A per-joint vector of as many numbers as the member's default holds (the
/// section's reader sizes the defaults to the arm's joints first). `member`
/// is a pointer to a member of T, or a generic lambda returning a reference
/// to one further down ([](auto& c) -> auto& { return c.params.stiffness; }).
template <class T, class Member>
Field<T> jointVector(const std::string& key, Member member, VectorRule rule = VectorRule()) {
  return {key,
          [key, member, rule](MapReader& m, T& t) {
            if (rule.presence == Presence::kOptional && !m.has(key)) return;
            Eigen::VectorXd& v = std::invoke(member, t);
            v = m.vector(key, static_cast<int>(v.size()), rule.one_number_for_all, rule.positive_only);
            if (rule.check) rule.check(m, key, v);
          },
          [key, member](YAML::Emitter& out, const T& t) { writeVector(out, key, std::invoke(member, t)); }};
}
template <class T>
Field<T> jointVector(const std::string& key, Eigen::VectorXd T::*member, VectorRule rule = VectorRule()) {
  return jointVector<T, Eigen::VectorXd T::*>(key, member, std::move(rule));
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
