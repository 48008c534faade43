#pragma once
// The plain comma-separated tables people write by hand (berths, wave climates): fields split on
// commas without quoting (a field that needs a comma is refused by its reader), blanks trimmed,
// numbers that must fill their field. One owner for what export/ and library/ both read.
#include <optional>
#include <string>
#include <vector>

namespace nearshore {

/// `text` without leading and trailing blanks (space, tab, CR, LF).
std::string trimmed(const std::string& text);

/// The fields of one line split on commas, each trimmed; a trailing comma gives an empty last field.
std::vector<std::string> csv_fields(const std::string& line);

/// A finite number that fills the whole (trimmed) field, else nullopt ("", "1.5 m", "nan", "1e999").
std::optional<double> finite_number(const std::string& field);

}  // namespace nearshore
