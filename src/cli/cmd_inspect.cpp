// centaur inspect F.h5 [--primitive NAME] [--json]
// Summarises each primitive of a primitive file: solve info, duration, contact phases per foot, flight,
// apex base height, peak contact forces and joint forces. With --json the last stdout line is one object
// {"file": ..., "primitives": [{...}, ...]} (times in s, heights in m, forces in N; absent times are null).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "cli/command.hpp"
#include "common/error.hpp"
#include "data/primitive_io.hpp"
#include "data/primitive_summary.hpp"

namespace centaur::cli {
namespace {

struct InspectArgs {
  std::string file;
  std::string primitive;
  bool json = false;
};

nlohmann::json orNull(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json intervals(const std::vector<data::TimeInterval>& v) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& iv : v) j.push_back({iv.start, iv.end});
  return j;
}

const char* kJointNames[12] = {"FL x", "FL y", "FL z", "FR x", "FR y", "FR z",
                               "RL x", "RL y", "RL z", "RR x", "RR y", "RR z"};

nlohmann::json toJson(const data::Primitive& p, const data::PrimitiveSummary& s) {
  nlohmann::json j;
  j["name"] = s.name;
  j["samples"] = s.samples;
  j["duration_s"] = s.duration;
  j["shooting_intervals"] = s.shooting_intervals;
  j["solve"] = {{"status", s.solve.status},
                {"iterations", s.solve.iterations},
                {"solve_time_s", s.solve.solve_time_s},
                {"cost", s.solve.cost},
                {"max_constraint_violation", s.solve.max_constraint_violation},
                {"backend", s.solve.backend}};
  j["flight"] = {{"time_s", s.flight_time},
                 {"take_off_s", orNull(s.take_off_time)},
                 {"touch_down_s", orNull(s.touch_down_time)},
                 {"intervals", intervals(s.flight)}};
  j["apex"] = {{"base_height_m", orNull(s.apex_height)},
               {"time_s", orNull(s.apex_time)},
               {"gain_m", orNull(s.apex_gain)},
               {"start_height_m", orNull(s.start_height)},
               {"end_height_m", orNull(s.end_height)}};
  nlohmann::json feet = nlohmann::json::array();
  for (const auto& f : s.feet) {
    feet.push_back({{"name", f.name},
                    {"stance", intervals(f.stance)},
                    {"swing", intervals(f.swing)},
                    {"stance_time_s", f.stance_time},
                    {"lift_off_s", orNull(f.lift_off_time)},
                    {"touch_down_s", orNull(f.touch_down_time)},
                    {"peak_force_norm_N", f.peak_force_norm},
                    {"peak_force_norm_time_s", f.peak_force_norm_time},
                    {"peak_force_z_N", orNull(f.peak_force_z)},
                    {"peak_force_z_time_s", f.peak_force_z_time}});
  }
  j["feet"] = feet;
  j["peak_abs_tau"] = {{"value_N", s.peak_abs_tau},
                       {"joint", s.peak_abs_tau_joint >= 0 ? nlohmann::json(kJointNames[s.peak_abs_tau_joint])
                                                           : nlohmann::json(nullptr)},
                       {"time_s", s.peak_abs_tau_time}};
  nlohmann::json model = nlohmann::json::object();
  for (const auto& [k, v] : p.scalars) model[k] = orNull(v);
  for (const auto& [k, v] : p.vectors) model[k] = v;
  for (const auto& [k, v] : p.strings) model[k] = v;
  j["metadata"] = model;
  return j;
}

std::string fmt(const char* format, double x) {
  if (!std::isfinite(x)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string intervalText(const std::vector<data::TimeInterval>& v) {
  if (v.empty()) return "none";
  std::string s;
  for (const auto& iv : v) s += (s.empty() ? "" : " ") + fmt("[%.3f", iv.start) + fmt(", %.3f)", iv.end);
  return s;
}

void printHuman(const data::Primitive& p, const data::PrimitiveSummary& s) {
  std::ostringstream o;
  o << s.name << "\n";
  o << "  solver      " << s.solve.status << (s.solve.solved() ? "" : "  (NOT SOLVED)") << ", " << s.solve.iterations
    << " iterations, " << fmt("%.3f s", s.solve.solve_time_s) << ", cost " << fmt("%.6g", s.solve.cost)
    << ", max constraint violation " << fmt("%.3g", s.solve.max_constraint_violation)
    << (s.solve.backend.empty() ? "" : ", backend " + s.solve.backend) << "\n";
  o << "  duration    " << fmt("%.3f s", s.duration) << " (" << s.samples << " samples, N_s = " << s.shooting_intervals
    << ")\n";
  if (s.flight.empty()) {
    o << "  flight      none (some foot always in contact)\n";
  } else {
    o << "  flight      " << fmt("%.3f s", s.flight_time) << ": take-off " << fmt("%.3f s", s.take_off_time)
      << ", touch-down " << fmt("%.3f s", s.touch_down_time) << "  " << intervalText(s.flight) << "\n";
  }
  o << "  apex        base z " << fmt("%.3f m", s.apex_height) << " at " << fmt("%.3f s", s.apex_time) << " ("
    << fmt("%+.3f m", s.apex_gain) << " from start " << fmt("%.3f m", s.start_height) << "; end "
    << fmt("%.3f m", s.end_height) << ")\n";
  char head[160];
  std::snprintf(head, sizeof head, "  %-4s %9s %9s %11s %11s %10s  %s\n", "foot", "lift-off", "touch-dn",
                "peak|F| N", "peak Fz N", "stance s", "contact intervals [s]");
  o << head;
  for (const auto& f : s.feet) {
    char line[200];
    std::snprintf(line, sizeof line, "  %-4s %9s %9s %11s %11s %10s  ", f.name.c_str(),
                  fmt("%.3f", f.lift_off_time).c_str(), fmt("%.3f", f.touch_down_time).c_str(),
                  fmt("%.1f", f.peak_force_norm).c_str(), fmt("%.1f", f.peak_force_z).c_str(),
                  fmt("%.3f", f.stance_time).c_str());
    o << line << intervalText(f.stance) << "\n";
  }
  o << "  peak |tau|  " << fmt("%.1f N", s.peak_abs_tau) << " ("
    << (s.peak_abs_tau_joint >= 0 ? kJointNames[s.peak_abs_tau_joint] : "-") << ") at "
    << fmt("%.3f s", s.peak_abs_tau_time) << "\n";
  if (!p.scalars.empty()) {  // metadata scalars, wrapped at ~100 columns
    std::string line = "  metadata   ";
    for (const auto& [k, v] : p.scalars) {
      const std::string item = " " + k + "=" + fmt("%.6g", v);
      if (line.size() + item.size() > 100 && line.size() > 13) {
        o << line << "\n";
        line = "             ";
      }
      line += item;
    }
    o << line << "\n";
  }
  std::cout << o.str();
}

int runInspect(const InspectArgs& a) {
  std::vector<data::Primitive> prims;
  if (!a.primitive.empty()) {
    prims.push_back(data::readPrimitive(a.file, a.primitive));
  } else {
    prims = data::readPrimitives(a.file);
    if (prims.empty()) {
      throw InputError(a.file + ": the file holds no primitive (no lower-body primitive group; an arm trajectory "
                                "is read by the ocp stabilizer, not by inspect)");
    }
  }
  std::cout << a.file << ": " << prims.size() << " primitive" << (prims.size() == 1 ? "" : "s") << "\n";
  nlohmann::json list = nlohmann::json::array();
  for (const auto& p : prims) {
    const data::PrimitiveSummary s = data::summarize(p);
    std::cout << "\n";
    printHuman(p, s);
    list.push_back(toJson(p, s));
  }
  std::cout << std::flush;
  if (a.json) printJsonLine(nlohmann::json{{"file", a.file}, {"primitives", list}});
  return kExitOk;
}

const Registrar registrar{Command{
    "inspect", "Summarise the primitives of an HDF5 primitive file (phases, flight, apex, peak forces)",
    [](CLI::App& sub) -> std::function<int()> {
      auto a = std::make_shared<InspectArgs>();
      sub.add_option("file", a->file, "primitive file written by `centaur plan` (.h5)")->required();
      sub.add_option("--primitive,-p", a->primitive, "only this primitive (group name)");
      sub.add_flag("--json", a->json, "print one JSON object {file, primitives} as the last line of stdout");
      return [a]() { return runInspect(*a); };
    }}};

}  // namespace
}  // namespace centaur::cli
