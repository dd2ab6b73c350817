// Errors. Bad user input (a file, a flag, a scene) throws InputError with a one-line
// message naming the file or flag; the command line turns it into exit code 2.
// Programmer errors are asserts. Per-pixel code never throws.
#pragma once

#include <stdexcept>
#include <string>

namespace proxima {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail_input(const std::string& message) { throw InputError(message); }

// Bad input that is a file which does not exist: exit code 2 like any InputError; the Python
// module raises FileNotFoundError for it.
class MissingFileError : public InputError {
 public:
  using InputError::InputError;
};

[[noreturn]] inline void fail_missing_file(const std::string& message) { throw MissingFileError(message); }

}  // namespace proxima
