// ctest-labels: unit sweep
// The journal of finished runs: records round-trip exactly (NaN included); a torn last line - what a kill -9 in
// the middle of a write leaves - is cut off on the next open and appending goes on after the last whole record;
// an edited journal (a broken line in the middle, a run twice, a run of another sweep) is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "common/error.hpp"
#include "support/temp_dir.hpp"
#include "sweep/journal.hpp"

using namespace centaur;
using namespace centaur::sweep;

namespace {

RunRecord record(std::int64_t run) {
  RunRecord r;
  r.run = run;
  r.outcome = run % 2 ? "fall" : "success";
  // Values that need all 17 digits; 0.125 * run is exact, so the value is the same whether or not the compiler
  // fuses the multiply and add (it may, differently at each inlined call, in a build with FMA).
  for (std::size_t i = 0; i < r.metrics.size(); ++i)
    r.metrics[i] = i == 4 ? std::nan("") : 0.125 * static_cast<double>(run) + 1.0 / (3.0 + static_cast<double>(i));
  if (run == 3) r.error = "a message with \"quotes\"\nand a newline";
  return r;
}

std::string readFile(const std::string& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(Journal, RoundTripAndTornLastLine) {
  const centaur_test::TempDir dir("journal");
  const std::string path = dir.file("journal.jsonl");
  {
    Journal j(path, 10);
    EXPECT_TRUE(j.records().empty());
    j.append({record(0), record(3)});
    j.append({record(7)});
  }
  std::ofstream(path, std::ios::app) << "{\"run\": 5, \"outcome\": \"succ";  // killed while writing
  {
    Journal j(path, 10);
    ASSERT_EQ(j.records().size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      const RunRecord want = record(k == 0 ? 0 : k == 1 ? 3 : 7), &got = j.records()[k];
      EXPECT_EQ(got.run, want.run);
      EXPECT_EQ(got.outcome, want.outcome);
      EXPECT_EQ(got.error, want.error);
      for (std::size_t i = 0; i < want.metrics.size(); ++i) {
        if (std::isnan(want.metrics[i])) {
          EXPECT_TRUE(std::isnan(got.metrics[i]));
        } else {
          EXPECT_EQ(std::memcmp(&got.metrics[i], &want.metrics[i], sizeof(double)), 0) << i;
        }
      }
    }
    j.append({record(5)});
  }
  const std::string text = readFile(path);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 4);
  EXPECT_EQ(text.find("succ\""), std::string::npos) << "the torn line was not cut off";
  EXPECT_EQ(Journal(path, 10).records().back().run, 5);
}

TEST(Journal, EditedJournalsAreRefused) {
  const centaur_test::TempDir dir("journal-bad");
  const std::string path = dir.file("journal.jsonl");
  {
    Journal j(path, 10);
    j.append({record(1), record(2)});
  }
  EXPECT_THROW(Journal(path, 2), InputError);  // run 2 is not a run of a 2-run sweep
  std::ofstream(path, std::ios::app) << toJson(record(1)).dump() << "\n";
  EXPECT_THROW(Journal(path, 10), InputError);  // run 1 twice
  std::ofstream(path, std::ios::trunc) << "not json\n" << toJson(record(1)).dump() << "\n";
  EXPECT_THROW(Journal(path, 10), InputError);
}
