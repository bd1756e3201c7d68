// ctest-labels: unit
// The page's compact encoding: int16 channels decode to within half a quantisation step of the input (so a
// pelvis height is exact to micrometres), constant and non-finite channels survive, base64 round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "report/channel_codec.hpp"

namespace report = centaur::report;

TEST(ChannelCodec, Int16ChannelsDecodeWithinHalfAStepOfTheirOwnRange) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::size_t rows = 500, channels = 7;
  const double range[channels] = {0.6, 30.0, 1e-3, 2.0, 2.0, 2.0, 2.0};  // per-channel spans
  std::vector<double> v(rows * channels);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < channels; ++c) v[r * channels + c] = 0.7 * c + 0.5 * range[c] * u(rng);
  }
  const nlohmann::json e = report::encodeInt16Channels(v, channels);
  EXPECT_EQ(e["rows"], rows);
  EXPECT_EQ(e["channels"], channels);
  const std::vector<double> d = report::decodeInt16Channels(e);
  ASSERT_EQ(d.size(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double step = e["scale"][i % channels].get<double>();
    EXPECT_LE(step, range[i % channels] / 65534.0 * 1.0000001);
    EXPECT_LE(std::abs(d[i] - v[i]), 0.5 * step * 1.000001) << "value " << i;
  }
  // 0.6 m of pelvis motion: a step of 9.2 micrometres.
  EXPECT_LT(e["scale"][0].get<double>(), 1e-5);
}

TEST(ChannelCodec, ConstantAndNonFiniteChannels) {
  const std::vector<double> v = {1.25, NAN, 1.25, 2.0, 1.25, INFINITY};
  const std::vector<double> d = report::decodeInt16Channels(report::encodeInt16Channels(v, 2));
  EXPECT_EQ(d[0], 1.25);
  EXPECT_EQ(d[2], 1.25);
  EXPECT_EQ(d[4], 1.25);
  EXPECT_EQ(d[3], 2.0);  // the only finite value of its channel
  EXPECT_THROW(report::encodeInt16Channels(v, 4), std::invalid_argument);
}

TEST(ChannelCodec, Base64OfFloat32AndBytesRoundTrips) {
  const std::vector<double> v = {0.0, -1.5, 3.25e-3, 1e6};
  const std::vector<std::uint8_t> b = report::decodeBase64(report::encodeFloat32(v));
  ASSERT_EQ(b.size(), 4 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    float f;
    std::memcpy(&f, b.data() + 4 * i, 4);
    EXPECT_EQ(f, static_cast<float>(v[i]));
  }
  const std::vector<std::uint8_t> bytes = {0, 1, 2, 250, 255};
  EXPECT_EQ(report::decodeBase64(report::encodeBytes(bytes)), bytes);
  EXPECT_EQ(report::encodeBytes({'M', 'a', 'n'}), "TWFu");  // RFC 4648's example
}
