#pragma once
/// @file
/// Names of enumerators, table-driven: one table per enum gives both
/// directions and the list of choices an error message names. Below every
/// layer (it includes nothing of the project), so config keys, the reference
/// type and the STATUS states all use the same three functions.
///
///   inline constexpr util::EnumName<Mode> kModeNames[] = {{Mode::kLockstep, "lockstep"}, ...};
///   util::nameOf(kModeNames, Mode::kInproc)   -> "inproc"
///   util::enumFrom(kModeNames, "realtime")    -> Mode::kRealtime (nullopt if unknown)
///   util::choicesOf(kModeNames)               -> "lockstep, realtime or inproc"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace lagrange::util {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

/// The name of `value`; the first entry's name if the table lacks it (a
/// table with every enumerator, which each table's unit test checks, never does).
template <class E, std::size_t N>
const char* nameOf(const EnumName<E> (&table)[N], E value) {
  for (const EnumName<E>& entry : table)
    if (entry.value == value) return entry.name;
  return table[0].name;
}

template <class E, std::size_t N>
std::optional<E> enumFrom(const EnumName<E> (&table)[N], std::string_view name) {
  for (const EnumName<E>& entry : table)
    if (name == entry.name) return entry.value;
  return std::nullopt;
}

/// "a, b or c": the choices, for messages that say what was expected.
template <class E, std::size_t N>
std::string choicesOf(const EnumName<E> (&table)[N]) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) out += i + 1 == N ? " or " : ", ";
    out += table[i].name;
  }
  return out;
}

}  // namespace lagrange::util
