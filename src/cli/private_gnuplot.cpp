#include "cli/private_gnuplot.hpp"

#include <stdlib.h>

#include <cctype>
#include <filesystem>

#include "cli/plot_primitive.hpp"  // runGnuplot
#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace centaur::cli {

namespace fs = std::filesystem;

namespace {

/// A private directory whose path is plain text (/tmp if TMPDIR holds other characters).
fs::path privateDirectory() {
  std::error_code ec;
  fs::path base = fs::temp_directory_path(ec);
  if (ec || base.string().find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./-") !=
                std::string::npos) {
    base = "/tmp";
  }
  std::string pattern = (base / "centaur-plot-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw RuntimeError("cannot create a temporary directory in " + base.string());
  return pattern;
}

}  // namespace

std::string gnuplotLiteral(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || std::string("_./+- ").find(c) != std::string::npos;
    out += ok ? c : '?';
  }
  return out + "'";
}

void drawPrivately(const std::string& data_path, const std::string& png_path,
                   const std::function<std::string(const std::string& data, const std::string& png)>& script) {
  const fs::path dir = privateDirectory();
  std::error_code ec;
  try {
    const fs::path data = dir / "data.dat", png = dir / "plot.png";
    fs::copy_file(data_path, data, ec);
    if (ec) throw RuntimeError("cannot copy " + data_path + ": " + ec.message());
    runGnuplot(script(data.string(), png.string()));
    if (!fs::exists(png, ec) || fs::file_size(png, ec) < 8) throw RuntimeError("gnuplot did not draw " + png_path);
    const std::string tmp = temporaryPathFor(png_path);
    fs::copy_file(png, tmp, fs::copy_options::overwrite_existing, ec);
    if (ec) throw RuntimeError("cannot write " + png_path + ": " + ec.message());
    commitFile(tmp, png_path);
  } catch (...) {
    fs::remove_all(dir, ec);
    throw;
  }
  fs::remove_all(dir, ec);
}

}  // namespace centaur::cli
