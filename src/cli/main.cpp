// centaur: plan, inspect, plot, simulate, compare and benchmark agile actions of CENTAURO.
// The single place where errors become exit codes (common/error.hpp), where the cleanup of temporaries on
// signals and exit is installed (common/cleanup.hpp) and where freed memory is kept in the process
// (common/retain_memory.hpp).
#include <cstdio>
#include <iostream>
#include <new>

#include "cli/app.hpp"
#include "common/cleanup.hpp"
#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/retain_memory.hpp"


namespace {
int report(const char* what, int code) {
  // Messages quote inputs; no control character of theirs reaches the terminal.
  std::cerr << "error: " << centaur::printable(what) << std::endl;
  return code;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace centaur;
  common::retainFreedMemory();  // repeated solves and simulations reuse their memory (no page faults)
  cleanup::install();
  cli::CliApp cli;
  std::function<int()> action;
  try {
    action = cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = cli.app().exit(e);
    return rc == 0 ? 0 : kExitBadInput;
  }
  try {
    return action();
  } catch (const InputError& e) {
    return report(e.what(), kExitBadInput);
  } catch (const RuntimeError& e) {
    return report(e.what(), kExitRuntime);
  } catch (const std::bad_alloc&) {
    return report("out of memory", kExitRuntime);
  } catch (const std::exception& e) {
    return report(e.what(), kExitRuntime);
  }
}
