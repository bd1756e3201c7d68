#pragma once
// gnuplot (Debian package gnuplot-nox) as the plotting back end of `centaur plot` and `centaur compare`.
// Untrusted text never reaches a gnuplot script unescaped:
//   - numbers go through data files, never through the script;
//   - gnuplot runs in a private temporary directory and the script names only fixed file names in it (its data
//     files and the PNG it writes), never a path given by the user;
//   - text that must be shown (titles, legends from an input file) goes through gnuplotQuote(), the one escaping
//     function: a single-quoted gnuplot string (no backquote substitution, no macro expansion, no escape
//     processing inside), control characters (a newline would end the command) replaced, quotes doubled.
// gnuplot is started without a shell (common/child_process.hpp) and killed if the command is interrupted.
#include <string>
#include <string_view>
#include <vector>

namespace centaur::cli {

/// True if a `gnuplot` executable is on PATH.
bool gnuplotAvailable();

/// `text` as a single-quoted gnuplot string literal: every control character becomes a space and every quote
/// is doubled; `enhanced`: the markup characters of gnuplot's enhanced text mode (^ _ @ & ~ { } \) are escaped
/// so they print as themselves.
std::string gnuplotQuote(std::string_view text, bool enhanced = false);

/// The file name the scripts of renderPng() write their PNG to (inside gnuplot's working directory).
inline constexpr const char* kGnuplotPng = "plot.png";

/// A data file of a script: written as `name` into gnuplot's working directory, from `text` or copied from
/// `source` (a path) when `source` is not empty. `name` is chosen by the program, never by the input.
struct GnuplotFile {
  std::string name;
  std::string text;
  std::string source;
};

/// Run `script` (which writes kGnuplotPng) in a private temporary directory holding `files`, then move the PNG to
/// `png_path` atomically (temporary sibling + rename; parent directories created). RuntimeError if gnuplot is
/// missing, fails or draws nothing; nothing is left behind then.
void renderPng(const std::string& script, const std::vector<GnuplotFile>& files, const std::string& png_path);

/// Run gnuplot on `script` in a fresh temporary directory; returns what gnuplot printed (stdout and stderr).
/// Throws RuntimeError if gnuplot is missing ("apt-get install gnuplot-nox") or exits non-zero.
std::string runGnuplot(const std::string& script);

}  // namespace centaur::cli
