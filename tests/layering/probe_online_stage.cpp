// A program that uses the online stage (a stabilizer and the primitive replay's data types) and nothing else:
// its shared libraries are what a controller-only deployment loads (checked by check_online_stage.cmake).
#include <cstdio>

#include "data/primitive.hpp"
#include "stabilizers/make_stabilizer.hpp"
#include "stabilizers/stabilizer.hpp"

int main() {
  centaur::data::Primitive p;
  const std::string yaml = centaur::stabilizerDefaultsYaml();
  std::printf("%s %zu\n", p.name.c_str(), yaml.size());
  return 0;
}
