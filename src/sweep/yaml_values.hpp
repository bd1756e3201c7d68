#pragma once
// Small YAML helpers of the sweep spec: values as normalised text (numbers exact), numbers and lists of numbers
// with messages naming the spec file and key.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace centaur::sweep {

/// True if the scalar's whole text is a finite number; its value in `x`.
bool scalarNumber(const YAML::Node& node, double& x);

/// A scalar or a (nested) list as one-line YAML with exact numbers: 0.10 -> "0.1", [1, 2.50] -> "[1, 2.5]";
/// strings as yaml-cpp emits them (quoted where YAML needs it). Mappings: InputError(file, key).
std::string valueText(const YAML::Node& node, const std::string& file, const std::string& key);

/// A number or a list of exactly `size` numbers (a number is repeated `size` times when `broadcast`).
std::vector<double> numbers(const YAML::Node& node, int size, bool broadcast, const std::string& file,
                            const std::string& key);

/// Exact numbers as YAML text: "0.5" for one number, "[0.5, -1]" for several (a list key's value).
std::string numbersText(const std::vector<double>& v);

/// Keys of the spec that become HDF5 column names, file names and plot labels: [A-Za-z0-9_.-], starting with a
/// letter or '_'. InputError(file, key) otherwise.
void checkKeyName(const std::string& name, const std::string& file, const std::string& key);

}  // namespace centaur::sweep
