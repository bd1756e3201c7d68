// ctest-labels: integration cli
// `centaur report` on bad input exits 2 naming the file and the dataset and writes no HTML (nor a temporary):
// an HDF5 file that is not a centaur log, a log cut short (bytes missing; a dataset with fewer rows than `t`), a
// primitive file given as a log, no input. A real short log gives a page (exit 0, --json line).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "data/hdf5.hpp"
#include "data/primitive_io.hpp"
#include "support/cli_run.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
namespace h5 = centaur::data::h5;
using centaur_test::CliRun;
using centaur_test::run;

namespace {

void copyPrefix(const std::string& from, const std::string& to, std::size_t bytes) {
  std::ifstream in(from, std::ios::binary);
  std::string data(bytes, '\0');
  in.read(data.data(), static_cast<std::streamsize>(bytes));
  std::ofstream(to, std::ios::binary).write(data.data(), in.gcount());
}

/// The log at `path` with dataset `name` replaced by one with `rows` rows (the columns kept).
void shortenDataset(const std::string& path, const std::string& name, hsize_t rows) {
  const h5::QuietErrors quiet;
  const h5::Writer w(path);
  h5::Id file = w.openFile(path);
  h5::Id ds(H5Dopen2(file.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  h5::Id space(H5Dget_space(ds.get()), H5Sclose);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.get())));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  ds.reset();
  ASSERT_GE(H5Ldelete(file.get(), name.c_str(), H5P_DEFAULT), 0);
  dims[0] = rows;
  std::size_t count = 1;
  for (hsize_t d : dims) count *= d;
  const std::vector<double> zeros(count, 0.0);
  w.doubles(file.get(), name, dims, zeros.data(), {"rad", nullptr, "shortened"});
}

}  // namespace

TEST(ReportCli, BadInputExits2NamingFileAndDatasetAndWritesNoHtml) {
  const centaur_test::TempDir dir("report-cli");
  const std::string log = dir.file("stand.h5");
  ASSERT_EQ(run("simulate stand --duration 0.05 --out " + log, false).code, 0);
  const std::string foreign = dir.file("foreign.h5");
  {
    const h5::Writer w(foreign);
    h5::Id f = w.createFile(foreign);
    const double x[3] = {1, 2, 3};
    w.doubles(f.get(), "x", {3}, x, {"m", nullptr, "not a log"});
  }
  copyPrefix(log, dir.file("cut.h5"), fs::file_size(log) / 2);
  fs::copy_file(log, dir.file("short.h5"));
  shortenDataset(dir.file("short.h5"), "base_pos", 10);
  centaur::data::writePrimitive(dir.file("plan.h5"), centaur::test::makeSyntheticJump("squat-jump"));
  std::ofstream(dir.file("text.h5")) << "not even HDF5\n";

  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {foreign, {"foreign.h5", "'format'", "not a centaur simulation log"}},
      {dir.file("cut.h5"), {"cut.h5", "truncated"}},
      {dir.file("short.h5"), {"short.h5", "'base_pos'", "(10, 3)"}},
      {dir.file("plan.h5"), {"plan.h5", "'format'", "centaur-primitive"}},
      {dir.file("text.h5"), {"text.h5", "not an HDF5 file"}},
      {dir.file("missing.h5"), {"missing.h5", "no such file"}},
      {log + " --rate 2", {"--rate"}},
      {log + " --primitive " + foreign, {"foreign.h5"}},
      {"", {"give a simulation log"}},
  };
  const std::size_t files_before = dir.entries().size();
  for (const auto& [args, words] : cases) {
    const CliRun r = run("report " + args + " --out " + dir.file("page.html"));
    EXPECT_EQ(r.code, 2) << args << "\n" << r.out;
    for (const auto& w : words) EXPECT_NE(r.out.find(w), std::string::npos) << args << ": no '" << w << "' in\n" << r.out;
  }
  EXPECT_EQ(dir.entries().size(), files_before) << "a page or a temporary was written";

  const CliRun ok = run("report " + log + " --out " + dir.file("stand.html") + " --json", false);
  ASSERT_EQ(ok.code, 0) << ok.out;
  const nlohmann::json j = nlohmann::json::parse(ok.last_line);
  EXPECT_EQ(j["runs"], 1);
  EXPECT_EQ(j["frames"], 6);  // 0.05 s at 100 Hz, both ends
  EXPECT_EQ(j["bytes"], fs::file_size(dir.file("stand.html")));
}
