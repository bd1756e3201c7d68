// Fuzz target: the command-line parser of `centaur` (cli/app.hpp, every registered verb with its options and
// validators). The input is the argument list, NUL-separated; only parsing runs (no verb is executed): a parse
// error is CLI11's ParseError (exit code 2 in main), anything else escaping is a finding.
#include <CLI/CLI.hpp>

#include "cli/app.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args = centaur_fuzz::splitNul(data, size, 24);
  args.insert(args.begin(), "centaur");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  static centaur::cli::CliApp app;  // built once; clear() forgets the previous parse
  try {
    app.app().clear();
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: unexpected exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}
