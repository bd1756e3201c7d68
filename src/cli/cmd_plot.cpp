// centaur plot F.h5 [--out F.png] [--primitive NAME] [--width PX] [--height PX] [--json]
// Draws each primitive like the lower plots of the paper's Fig. 3: contact forces, feet positions and waist
// position over time, flight and partial-support phases shaded (gnuplot, pngcairo).
// One primitive -> the --out file. Several primitives and no --primitive -> one PNG per primitive named
// <out stem>-<primitive name>.png next to --out. --out defaults to F with the extension .png.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/command.hpp"
#include "cli/plot_primitive.hpp"
#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/output_guard.hpp"
#include "data/primitive_io.hpp"

namespace centaur::cli {
namespace {

struct PlotArgs {
  std::string file;
  std::string out;
  std::string primitive;
  int width = 1200;
  int height = 1300;
  bool json = false;
};

/// A primitive's name as part of a file name: characters other than letters, digits, '.', '_' and '-' become
/// '_' (a group name from a file is untrusted), at most 100 of them.
std::string fileNamePart(const std::string& name) {
  std::string out;
  for (char c : name.substr(0, 100)) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '_' || c == '-';
    out += ok ? c : '_';
  }
  return out;
}

std::string outputFor(const std::string& out, const std::string& name, bool several) {
  if (!several) return out;
  const std::filesystem::path p(out);
  const std::string ext = p.has_extension() ? p.extension().string() : std::string(".png");
  return (p.parent_path() / (p.stem().string() + "-" + fileNamePart(name) + ext)).string();
}

int runPlot(const PlotArgs& a) {
  std::vector<std::string> names;
  if (!a.primitive.empty()) {
    names.push_back(a.primitive);
  } else {
    names = data::listPrimitives(a.file);
    if (names.empty()) throw InputError(a.file + ": the file holds no primitive (no group)");
  }
  std::string out = a.out;
  if (out.empty()) out = std::filesystem::path(a.file).replace_extension(".png").string();
  PlotOptions options;
  options.width_px = a.width;
  options.height_px = a.height;

  // Every primitive is read (and so validated) and every output named before the first PNG is written.
  std::vector<data::Primitive> prims;
  std::vector<NamedPath> pngs;
  for (const std::string& name : names) {
    prims.push_back(data::readPrimitive(a.file, name));
    pngs.push_back({names.size() > 1 ? "the plot of '" + excerpt(name) + "'" : "--out", outputFor(out, name, names.size() > 1)});
  }
  guardOutputs({{"the primitive file", a.file}}, pngs);

  nlohmann::json outputs = nlohmann::json::array();
  for (std::size_t i = 0; i < prims.size(); ++i) {
    plotPrimitive(prims[i], pngs[i].path, options);
    std::cout << "wrote " << pngs[i].path << " (" << excerpt(prims[i].name) << ")" << std::endl;
    outputs.push_back({{"primitive", prims[i].name}, {"png", pngs[i].path}});
  }
  if (a.json) printJsonLine(nlohmann::json{{"file", a.file}, {"outputs", outputs}});
  return kExitOk;
}

const Registrar registrar{Command{
    "plot", "Plot contact forces, feet and waist positions of the primitives in an HDF5 file (PNG, gnuplot)",
    [](CLI::App& sub) -> std::function<int()> {
      auto a = std::make_shared<PlotArgs>();
      sub.add_option("file", a->file, "primitive file written by `centaur plan` (.h5)")->required();
      sub.add_option("--out,-o", a->out,
                     "output PNG (default: the input with extension .png); with several primitives and no "
                     "--primitive, one file <stem>-<name>.png per primitive");
      sub.add_option("--primitive,-p", a->primitive, "plot only this primitive (group name)");
      sub.add_option("--width", a->width, "image width [px]")->check(CLI::Range(400, 6000));
      sub.add_option("--height", a->height, "image height [px]")->check(CLI::Range(400, 6000));
      sub.add_flag("--json", a->json, "print one JSON object {file, outputs} as the last line of stdout");
      return [a]() { return runPlot(*a); };
    }}};

}  // namespace
}  // namespace centaur::cli
