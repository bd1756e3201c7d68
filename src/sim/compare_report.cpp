#include "sim/compare_report.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "common/error.hpp"

namespace centaur::sim {

namespace {

std::optional<double> extraValue(const RunSummary& s, const std::string& key) {
  auto it = s.extra.find(key);
  if (it == s.extra.end()) return std::nullopt;
  return it->second;
}

std::string fixed(const std::optional<double>& v, int digits) {
  if (!v || !std::isfinite(*v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, *v);
  return buf;
}

nlohmann::json value(const std::optional<double>& v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}

/// Markdown cell text: pipes escaped, line breaks flattened.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n' || c == '\r') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

CompareRow makeCompareRow(const std::string& scenario, const std::string& stabilizer, const BatchResult& result,
                          const std::string& log_path) {
  CompareRow row;
  row.scenario = scenario;
  row.stabilizer = stabilizer;
  if (result.status != BatchResult::Status::Completed) {
    row.outcome = "error";
    row.error = result.error.empty() ? std::string("the run did not complete") : result.error;
    return row;
  }
  const RunSummary& s = result.summary;
  row.outcome = s.outcome;
  row.peak_pitch_deg = s.peak_pitch_deg;
  row.pitch_rms_deg = extraValue(s, "pitch_rms_deg");
  row.max_torque_ratio = s.max_torque_ratio;
  row.wall_contact_s = extraValue(s, "wall_contact_s");
  row.real_time_factor = s.real_time_factor;
  row.wall_time_s = s.wall_time_s;
  row.duration_s = s.duration_s;
  if (s.fall_time_s >= 0.0) row.fall_time_s = s.fall_time_s;
  row.extra = s.extra;
  row.log = log_path;
  return row;
}

std::string compareMarkdown(const std::vector<CompareRow>& rows) {
  std::ostringstream md;
  md << "| jump | mode | outcome | peak pitch [deg] | pitch RMS [deg] | max torque ratio | wall contact [s] | "
        "real-time factor |\n"
     << "|---|---|---|---:|---:|---:|---:|---:|\n";
  for (const auto& r : rows) {
    md << "| " << cell(r.scenario) << " | " << cell(r.stabilizer) << " | " << cell(r.outcome) << " | "
       << fixed(r.peak_pitch_deg, 2) << " | " << fixed(r.pitch_rms_deg, 2) << " | " << fixed(r.max_torque_ratio, 3)
       << " | " << fixed(r.wall_contact_s, 3) << " | " << fixed(r.real_time_factor, 2) << " |\n";
  }
  bool first = true;
  for (const auto& r : rows) {
    if (r.error.empty()) continue;
    if (first) md << "\nFailed runs:\n\n";
    first = false;
    md << "- " << cell(r.scenario) << " / " << cell(r.stabilizer) << ": " << cell(r.error) << "\n";
  }
  return md.str();
}

nlohmann::json compareJson(const std::vector<CompareRow>& rows) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& r : rows) {
    nlohmann::json j;
    j["scenario"] = r.scenario;
    j["stabilizer"] = r.stabilizer;
    j["outcome"] = r.outcome;
    j["peak_pitch_deg"] = value(r.peak_pitch_deg);
    j["pitch_rms_deg"] = value(r.pitch_rms_deg);
    j["max_torque_ratio"] = value(r.max_torque_ratio);
    j["wall_contact_s"] = value(r.wall_contact_s);
    j["real_time_factor"] = value(r.real_time_factor);
    j["wall_time_s"] = value(r.wall_time_s);
    j["duration_s"] = value(r.duration_s);
    j["fall_time_s"] = value(r.fall_time_s);
    j["log"] = r.log.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.log);
    if (!r.error.empty()) j["error"] = r.error;
    for (const auto& [name, v] : r.extra) {
      if (!j.contains(name)) j[name] = value(v);
    }
    a.push_back(std::move(j));
  }
  return a;
}

std::string pitchCsv(const std::vector<std::string>& names, const std::vector<PitchSeries>& series) {
  if (names.size() != series.size()) {
    throw RuntimeError("pitchCsv: " + std::to_string(names.size()) + " names for " + std::to_string(series.size()) +
                       " series");
  }
  // Merge on the time axis, keyed by whole nanoseconds.
  std::map<long long, std::vector<double>> table;
  for (std::size_t c = 0; c < series.size(); ++c) {
    const PitchSeries& s = series[c];
    if (s.t.size() != s.pitch_deg.size()) {
      throw RuntimeError("pitchCsv: series '" + names[c] + "' has " + std::to_string(s.t.size()) + " times and " +
                         std::to_string(s.pitch_deg.size()) + " values");
    }
    for (std::size_t k = 0; k < s.t.size(); ++k) {
      auto& row = table[std::llround(s.t[k] * 1e9)];
      if (row.empty()) row.assign(series.size(), std::nan(""));
      row[c] = s.pitch_deg[k];
    }
  }
  std::ostringstream csv;
  csv << "t_s";
  for (const auto& n : names) csv << ',' << n;
  csv << '\n';
  char buf[40];
  for (const auto& [key, row] : table) {
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(key) * 1e-9);
    csv << buf;
    for (double v : row) {
      if (std::isfinite(v)) {
        std::snprintf(buf, sizeof buf, ",%.6f", v);
        csv << buf;
      } else {
        csv << ",nan";
      }
    }
    csv << '\n';
  }
  return csv.str();
}

}  // namespace centaur::sim
