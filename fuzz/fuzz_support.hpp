#pragma once
// Shared by the fuzz targets (fuzz/README.md): what an input may legitimately cause, and in-memory helpers.
//   - centaur::InputError is the promised answer to bad input (exit code 2): the target returns normally;
//   - anything else escaping (another exception, a crash, a sanitizer report, a hang, a huge allocation) is a
//     finding: the target aborts so that libFuzzer keeps the input.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "common/error.hpp"

namespace centaur_fuzz {

/// Run `f`; InputError is fine, anything else aborts with its message.
template <class F>
void expectOnlyInputErrors(F&& f) {
  try {
    f();
  } catch (const centaur::InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: unexpected exception: %s\n", e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "FINDING: unexpected non-standard exception\n");
    std::abort();
  }
}

/// The input split at NUL bytes: the first part and up to `max_rest` further parts.
inline std::vector<std::string> splitNul(const std::uint8_t* data, std::size_t size, std::size_t max_parts) {
  std::vector<std::string> parts(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0 && parts.size() < max_parts) {
      parts.emplace_back();
    } else {
      parts.back() += static_cast<char>(data[i]);
    }
  }
  return parts;
}

/// A file on tmpfs (or /tmp) holding `text`, for loaders that take a path; one per process, rewritten per input.
inline std::string scratchFile(const std::string& text, const char* suffix) {
  static const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
  const std::string path = dir + "/centaur-fuzz-" + std::to_string(getpid()) + suffix;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path;
}

}  // namespace centaur_fuzz
