// error.h - the one exception type of the engine. Its message is meant for the
// user: it names the file and the field (or the phase and the step) at fault.
#pragma once
#include <stdexcept>
#include <string>

namespace ff {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace ff
