// centaur report [LOG.h5]... [--primitive F.h5] [--primitive-name NAME] [--out F.html] [--rate HZ] [--model F.xml]
//                [--title T] [--json]
// One self-contained HTML page (docs/report.md): the 3D replay of each simulated run (robot from the MJCF's geoms,
// ground, wall, contact-force arrows, the plan as a ghost), plots synced with it and the run's metadata; several
// logs get a run selector. A primitive file alone shows each of its plans the same way.
// Exit codes: 0 written; 2 bad input (nothing written); 4 I/O failure.
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/command.hpp"
#include "common/error.hpp"
#include "common/output_guard.hpp"
#include "report/report.hpp"

namespace centaur::cli {
namespace {

struct ReportArgs {
  std::vector<std::string> logs;
  std::string primitive, primitive_name, out, model, title;
  double rate = 100.0;
  bool json = false;
};

int runReport(const ReportArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  if (a.logs.empty() && a.primitive.empty()) {
    throw InputError("report: give a simulation log (LOG.h5) or a primitive file (--primitive F.h5)");
  }
  std::string out = a.out;
  if (out.empty()) out = std::filesystem::path(a.logs.empty() ? a.primitive : a.logs.front()).replace_extension(".html");
  std::vector<NamedPath> inputs{{"--primitive", a.primitive}, {"--model", a.model}};
  for (const std::string& log : a.logs) inputs.push_back({"the log", log});
  guardOutputs(inputs, {{"--out", out}});
  report::ReportOptions options;
  options.title = a.title;
  options.pose_rate_hz = a.rate;
  options.model_path = a.model;
  const report::ReportStats s =
      report::writeReport(out, report::runSources(a.logs, a.primitive, a.primitive_name), options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "report: " << s.runs << " run" << (s.runs == 1 ? "" : "s") << ", " << s.frames << " frames, "
            << s.bytes / 1024 << " KiB in " << seconds << " s\nwrote " << out << "\n";
  if (a.json) {
    printJsonLine(nlohmann::json{{"file", out},
                                 {"bytes", s.bytes},
                                 {"runs", s.runs},
                                 {"frames", s.frames},
                                 {"generation_s", seconds}}
                      .dump());
  }
  return kExitOk;
}

const Registrar registrar{Command{
    "report",
    "one self-contained HTML page: 3D replay of simulated runs (and plans), synced plots, metadata",
    [](CLI::App& sub) -> std::function<int()> {
      auto a = std::make_shared<ReportArgs>();
      sub.add_option("logs", a->logs, "simulation logs (centaur simulate --out LOG.h5); several get a run selector");
      sub.add_option("--primitive", a->primitive,
                     "primitive file: the plan drawn as a ghost (alone: every plan of the file)");
      sub.add_option("--primitive-name", a->primitive_name,
                     "the primitive of the file to use (default: the one named like the log's scenario)");
      sub.add_option("--out", a->out, "the HTML file (default: the first input with extension .html)");
      sub.add_option("--rate", a->rate, "body poses per second of replay [10, 1000] Hz")
          ->check(finiteRange(10.0, 1000.0))
          ->capture_default_str();
      sub.add_option("--model", a->model, "MJCF to draw (default: the model the log's run simulated)");
      sub.add_option("--title", a->title, "page title");
      sub.add_flag("--json", a->json, "print one JSON object {file, bytes, runs, frames, generation_s} last");
      return [a]() { return runReport(*a); };
    }}};

}  // namespace
}  // namespace centaur::cli
