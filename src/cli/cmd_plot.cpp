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

std::string outputFor(const std::string& out, const std::string& name, bool several) {
  if (!several) return out;
  const std::filesystem::path p(out);
  const std::string ext = p.has_extension() ? p.extension().string() : std::string(".png");
  return (p.parent_path() / (p.stem().string() + "-" + name + ext)).string();
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

  nlohmann::json outputs = nlohmann::json::array();
  for (const std::string& name : names) {
    const data::Primitive p = data::readPrimitive(a.file, name);
    const std::string png = outputFor(out, name, names.size() > 1);
    plotPrimitive(p, png, options);
    std::cout << "wrote " << png << " (" << name << ")" << std::endl;
    outputs.push_back({{"primitive", name}, {"png", png}});
  }
  if (a.json) printJsonLine(nlohmann::json{{"file", a.file}, {"outputs", outputs}}.dump());
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
