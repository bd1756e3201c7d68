#pragma once
// Errors that reach the user, each with the process exit code the CLI promises.
//   0 success, 2 bad input (file/key/range named), 3 solver did not converge (output written and flagged),
//   4 runtime failure (I/O, simulator).
#include <stdexcept>
#include <string>

namespace centaur {

enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitBadInput = 2, kExitNotConverged = 3, kExitRuntime = 4 };

/// Bad user input: a configuration file, key or value outside its allowed range.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
  /// "<file>: key '<key>': <message>", the form every bad-input message takes.
  InputError(const std::string& file, const std::string& key, const std::string& message)
      : std::runtime_error(file + ": key '" + key + "': " + message) {}
};

/// A failure of the machine or environment (I/O, simulator), not of the input.
class RuntimeError : public std::runtime_error {
 public:
  explicit RuntimeError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace centaur
