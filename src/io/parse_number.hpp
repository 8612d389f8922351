#pragma once
// A text field as a number, the way every text reader takes it: std::from_chars (no locale),
// an optional leading '+', and nothing left over.
#include <charconv>
#include <string_view>

namespace horizon::detail {

inline bool parse_number(std::string_view field, double& value) {
  const char* first = field.data() + (!field.empty() && field[0] == '+');
  const auto [end, error] = std::from_chars(first, field.data() + field.size(), value);
  return error == std::errc() && end == field.data() + field.size();
}

}  // namespace horizon::detail
