#pragma once
// The simulation log format "centaur-sim-log 1" (schema in docs/sim.md): one row per logged control period,
// one dataset per signal, every dataset with string attributes `units` and `description`; root attributes
// joint_names, contact_bodies (string lists), config (effective YAML), scenario, format, units, and optionally
// summary (the run's outcome and metrics as one JSON object; logs written before it existed lack it).
//
// The dataset table below is the single source of truth for names, shapes and units: the simulator's writer
// (sim::SimLog) and every reader (compare, report, sweeps) go through it.
// Conventions: quaternions w, x, y, z (attribute `quaternion_order`); N samples, n joints, c contact bodies.
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "data/file_image.hpp"
#include "data/row_matrix.hpp"

namespace centaur::data {

inline constexpr const char* kSimLogFormat = "centaur-sim-log 1";

/// Most samples (rows) a log may hold: one hour at 1 kHz. The simulator refuses a run whose log would be larger.
inline constexpr std::size_t kMaxLogSamples = 3600001;
/// Most joints (and contact bodies) a log may name.
inline constexpr std::size_t kMaxLogJoints = 1000;

/// The trailing shape of a log dataset.
enum class LogColumns { kNone, kJoints, k3, k4, k6, kContacts3 };

struct LogDataset {
  const char* name;
  LogColumns columns;
  const char* units;
  const char* description;
};

/// Every dataset of the format, in the order they are written.
const std::vector<LogDataset>& simLogDatasets();

/// What a log describes beside its datasets.
struct SimLogHeader {
  std::vector<std::string> joint_names;     ///< n, MJCF actuator order
  std::vector<std::string> contact_bodies;  ///< c
  std::string config_yaml;                  ///< the effective configuration of the run
  std::string scenario;
  std::string summary_json;                 ///< the run's outcome and metrics (JSON object); "" = not recorded
  std::size_t samples = 0;                  ///< N
};

/// Dims of `dataset` for a log with this header: {N} or {N, cols} or {N, c, 3}.
std::vector<unsigned long long> logDatasetDims(const LogDataset& dataset, const SimLogHeader& header);

/// Writes a log atomically (temporary file, then rename). `data` maps every dataset name of simLogDatasets() to
/// its row-major values (N x columns). RuntimeError on I/O failure or a missing/mis-sized dataset.
void writeSimLog(const std::string& path, const SimLogHeader& header,
                 const std::map<std::string, const std::vector<double>*>& data);

/// A log opened for reading. The constructor checks the format attribute, the header, the shape of every
/// dataset of the table and the time axis (finite, increasing; nothing else is read); read() checks that each
/// dataset it reads holds finite values only. InputError naming the file and the dataset or attribute
/// otherwise (e.g. a primitive file given as a log).
class SimLogFile {
 public:
  explicit SimLogFile(const std::string& path);
  explicit SimLogFile(const FileImage& image);
  ~SimLogFile();
  SimLogFile(const SimLogFile&) = delete;
  SimLogFile& operator=(const SimLogFile&) = delete;

  const std::string& path() const;
  const SimLogHeader& header() const { return header_; }
  /// Dataset `name` of the table as an N x columns matrix (wheel_force: N x 3c). InputError if not in the table.
  RowMatrix read(const std::string& name) const;
  Eigen::VectorXd time() const;

 private:
  void open();
  struct Impl;
  std::unique_ptr<Impl> impl_;
  SimLogHeader header_;
};

}  // namespace centaur::data
