#pragma once
/// @file
/// `lagrange sweep`, a row's axis values typed as the scenario reads them
/// (#54 item 3). The plan keeps each value as the YAML text it sets
/// (plan.json `params`, the `--set` of the run); the rows and the table hold
/// it as a value: a number as a JSON number, a list (a vector gain) as a JSON
/// list, `true`/`false` as a bool, a map as an object, any other text as a
/// string. Rows written before held every value that is not a number as its
/// YAML text ("controller.kd": "[5.0, 0.4]"); they are read back typed.
/// In sweep.csv an axis whose every value is a list of n numbers is n
/// columns, KEY[0] .. KEY[n-1] (docs/sweeps.md says why).

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lagrange::tools {

/// The value an axis's YAML text gives a row: a plain scalar `true` or
/// `false` a bool; `~`, `null` or nothing null; a plain scalar that is a
/// finite number (all of it, as strtod reads it) a number (a double);
/// another scalar (a quoted one too) its text; a list a JSON list and a map
/// a JSON object of the same, element by element. Text that is not YAML,
/// or nested more than 16 levels, stays the text it is.
nlohmann::ordered_json typedParam(const std::string& yaml_text);

/// A row written before axis values were typed: each parameter column whose
/// value is a string holding a YAML list, a map, `true`/`false` or a quoted
/// scalar is replaced by typedParam of it. A number was a number then too,
/// and any other string is a string now as it was. (A string value whose
/// text looks like a YAML list or bool, which only a quoted YAML value
/// gives, reads back as that list or bool: no scenario key takes such a string.)
void typeOldParams(nlohmann::ordered_json& row, const std::vector<std::string>& param_columns);

/// One column of sweep.csv from a parameter column: the whole value
/// (`element` -1), or element `element` of a list.
struct CsvParamColumn {
  std::string name;    ///< the CSV header's name: KEY, or KEY[i]
  std::string column;  ///< the row's key
  int element = -1;
};

/// The CSV columns of the parameter columns over these rows: a column whose
/// every value (of the rows that have one) is a list of the same n >= 1
/// numbers is n columns KEY[0] .. KEY[n-1]; any other is one column KEY.
std::vector<CsvParamColumn> csvParamColumns(const std::vector<std::string>& param_columns,
                                            const std::map<long, nlohmann::ordered_json>& rows);

/// A value as one CSV field: empty for null, 1 or 0 for a bool, a number as
/// the shortest text that reads back as it, a string as it is, a list or map
/// as its JSON text; quoted (RFC 4180) when it holds a comma, a quote or a
/// newline (the newline then written as a space).
std::string csvField(const nlohmann::ordered_json& v);

}  // namespace lagrange::tools
