#pragma once
// The error every trajectory reader and parameter loader throws: its message
// names the file and, where there is one, the line and field at fault.
#include <stdexcept>
#include <string>

namespace probes {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace probes
