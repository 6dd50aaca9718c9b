#pragma once
#include <stdexcept>

namespace granchain {

// Bad input from the user: reported as one line naming the parameter and its valid range,
// exit code 2, and nothing written.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace granchain
