#pragma once
/// \file error.hpp
/// The one exception type horizon throws for bad input and failed resources.
#include <stdexcept>
#include <string>

namespace horizon {

/// Thrown for anything the caller can fix: bad coordinates, a bad horizon, a malformed file,
/// an unwritable output. The message names the file, line or point index at fault.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace horizon
