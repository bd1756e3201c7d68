// ctest-labels: unit
// `centaur plot`'s drawing function on the synthetic jump: a real PNG of the requested size, with curves in
// every foot colour and the flight phase shaded; atomic output; a clear error without gnuplot.
// Set CENTAUR_TEST_OUTPUT_DIR to keep the drawn PNG (and the primitive file) for a look.
#include <gtest/gtest.h>

#include "support/temp_dir.hpp"
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "common/error.hpp"
#include "data/primitive_io.hpp"
#include "support/synthetic_primitive.hpp"

// The CLI is an executable, not a library: compile its plotting helper into this test directly.
#include "cli/gnuplot.cpp"         // NOLINT(bugprone-suspicious-include)
#include "cli/plot_primitive.cpp"  // NOLINT(bugprone-suspicious-include)

namespace fs = std::filesystem;

namespace {

using centaur_test::TempDir;

struct PngInfo {
  unsigned width = 0, height = 0;
};

/// Width and height from the PNG signature and IHDR chunk.
PngInfo pngHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(24, '\0');
  in.read(head.data(), 24);
  EXPECT_EQ(head.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(head.substr(12, 4), "IHDR");
  auto be32 = [&](int o) {
    unsigned v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(head[static_cast<std::size_t>(o + i)]);
    return v;
  };
  return {be32(16), be32(20)};
}

/// Pixel colour histogram of a PNG, decoded by gnuplot itself (libgd) into a table "x y r g b a".
std::map<unsigned, std::size_t> colourHistogram(const std::string& png, std::size_t& pixels) {
  const std::string table = png + ".txt";
  centaur::cli::runGnuplot("set table '" + table + "'\nplot '" + png +
                           "' binary filetype=png with rgbimage\nunset table\n");
  std::ifstream in(table);
  std::map<unsigned, std::size_t> hist;
  std::string line;
  pixels = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double x, y, r, g, b;
    if (!(s >> x >> y >> r >> g >> b)) continue;
    ++hist[(static_cast<unsigned>(r) << 16) | (static_cast<unsigned>(g) << 8) | static_cast<unsigned>(b)];
    ++pixels;
  }
  fs::remove(table);
  return hist;
}

}  // namespace

TEST(PlotPrimitive, DrawsANonBlankFigureWithAllCurvesAndShading) {
  if (!centaur::cli::gnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  TempDir dir;
  const auto jump = centaur::test::makeSyntheticJump("squat-jump");
  const std::string png = dir.file("sub/jump.png");
  centaur::cli::PlotOptions options;
  options.width_px = 600;
  options.height_px = 650;
  centaur::cli::plotPrimitive(jump, png, options);

  const PngInfo info = pngHeader(png);
  EXPECT_EQ(info.width, 600u);
  EXPECT_EQ(info.height, 650u);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"sub"});
  EXPECT_EQ(fs::directory_iterator(dir.file("sub"))->path().filename(), "jump.png");  // no temporary left

  std::size_t pixels = 0;
  const auto hist = colourHistogram(png, pixels);
  ASSERT_EQ(pixels, 600u * 650u);
  auto count = [&](unsigned rgb) {
    const auto it = hist.find(rgb);
    return it == hist.end() ? std::size_t{0} : it->second;
  };
  const std::size_t white = count(0xffffff);
  // Mostly background, but well populated: axes, text, curves, shading.
  EXPECT_GT(white, pixels / 3);
  EXPECT_LT(white, pixels * 95 / 100);
  // The flight phase (0.3 s of 1 s, three panels) is shaded; the partial-support phase too.
  EXPECT_GT(count(0xc9d6e8), pixels / 50);
  EXPECT_GT(count(0xfbefc5), 200u);
  // Every foot colour is drawn (lines are antialiased: count exact-colour core pixels).
  for (unsigned rgb : {0x1f77b4u, 0xff7f0eu, 0x2ca02cu, 0xd62728u}) EXPECT_GT(count(rgb), 200u) << std::hex << rgb;
  EXPECT_GT(hist.size(), 50u);  // antialiased text and lines: many distinct colours

  if (const char* keep = std::getenv("CENTAUR_TEST_OUTPUT_DIR")) {
    fs::create_directories(keep);
    centaur::cli::PlotOptions full;
    centaur::cli::plotPrimitive(jump, (fs::path(keep) / "synthetic-jump.png").string(), full);
    centaur::data::writePrimitives((fs::path(keep) / "synthetic.h5").string(),
                                      {jump, centaur::test::makeSyntheticJump("second-jump", 0.5)});
  }
}

TEST(PlotPrimitive, FailingGnuplotLeavesNoFileAndMissingGnuplotSaysHowToInstall) {
  if (!centaur::cli::gnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  TempDir dir;
  // A gnuplot error is reported with gnuplot's message.
  try {
    centaur::cli::runGnuplot("plot this_is_not_a_function(x)\n");
    ADD_FAILURE() << "no exception";
  } catch (const centaur::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot failed"), std::string::npos) << e.what();
  }
  // A primitive too short to plot is bad input, and nothing is written.
  auto empty = centaur::test::makeSyntheticJump("j");
  empty.t.resize(1);
  EXPECT_THROW(centaur::cli::plotPrimitive(empty, dir.file("x.png")), centaur::InputError);
  EXPECT_TRUE(dir.entries().empty());

  // Without gnuplot on PATH: RuntimeError naming the package.
  const char* old = std::getenv("PATH");
  const std::string saved = old != nullptr ? old : "";
  ::setenv("PATH", dir.file("nowhere").c_str(), 1);
  std::string msg;
  try {
    centaur::cli::plotPrimitive(centaur::test::makeSyntheticJump("j"), dir.file("y.png"));
  } catch (const centaur::RuntimeError& e) {
    msg = e.what();
  }
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_NE(msg.find("apt-get install gnuplot-nox"), std::string::npos) << msg;
  EXPECT_TRUE(dir.entries().empty());
}
