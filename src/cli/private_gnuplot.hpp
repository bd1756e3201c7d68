#pragma once
// gnuplot without untrusted text in its script: the data file is copied into a private temporary directory whose
// path is plain ([A-Za-z0-9_./-]), the script names only that copy and its PNG there, and every other string it
// holds goes through gnuplotLiteral. The PNG is then moved to its target atomically (temporary sibling, rename).
#include <functional>
#include <string>

namespace centaur::cli {

/// `s` as a single-quoted gnuplot string, every character outside [A-Za-z0-9_./+-] and space replaced by '?'
/// (for our own labels: keys and values the sweep spec restricts to that set, jump and mode names).
std::string gnuplotLiteral(const std::string& s);

/// `script(data, png)` gives the script for the private copy `data` of `data_path` and the private output `png`;
/// it runs (runGnuplot) and the PNG is moved to `png_path`. RuntimeError on failure (nothing left behind).
void drawPrivately(const std::string& data_path, const std::string& png_path,
                   const std::function<std::string(const std::string& data, const std::string& png)>& script);

}  // namespace centaur::cli
