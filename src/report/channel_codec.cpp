#include "report/channel_codec.hpp"

#include <yaml-cpp/binary.h>  // YAML::EncodeBase64 / DecodeBase64 (Debian's yaml-cpp)

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace centaur::report {

namespace {

constexpr double kSteps = 65534.0;  // int16 values -32767..32767 span the channel's range

template <typename T>
std::string base64Of(const std::vector<T>& v) {
  return YAML::EncodeBase64(reinterpret_cast<const unsigned char*>(v.data()), v.size() * sizeof(T));
}

}  // namespace

nlohmann::json encodeInt16Channels(const std::vector<double>& values, std::size_t channels) {
  if (channels == 0 || values.size() % channels != 0) {
    throw std::invalid_argument("encodeInt16Channels: values are not rows x channels");
  }
  const std::size_t rows = values.size() / channels;
  std::vector<double> offset(channels, 0.0), scale(channels, 1.0);
  for (std::size_t c = 0; c < channels; ++c) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t r = 0; r < rows; ++r) {
      const double x = values[r * channels + c];
      if (!std::isfinite(x)) continue;
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    if (lo > hi) continue;  // no finite value: offset 0
    offset[c] = 0.5 * (lo + hi);
    scale[c] = hi > lo ? (hi - lo) / kSteps : 1.0;
  }
  std::vector<std::int16_t> q(values.size(), 0);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < channels; ++c) {
      const double x = values[r * channels + c];
      if (!std::isfinite(x)) continue;
      const double k = std::round((x - offset[c]) / scale[c]);
      q[r * channels + c] = static_cast<std::int16_t>(std::clamp(k, -32767.0, 32767.0));
    }
  }
  return {{"rows", rows}, {"channels", channels}, {"offset", offset}, {"scale", scale}, {"int16", base64Of(q)}};
}

std::vector<double> decodeInt16Channels(const nlohmann::json& e) {
  const auto rows = e.at("rows").get<std::size_t>(), channels = e.at("channels").get<std::size_t>();
  const std::vector<double> offset = e.at("offset"), scale = e.at("scale");
  const std::vector<std::uint8_t> bytes = decodeBase64(e.at("int16").get<std::string>());
  if (bytes.size() != rows * channels * 2) throw std::invalid_argument("decodeInt16Channels: wrong byte count");
  std::vector<double> out(rows * channels);
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::int16_t v;
    std::memcpy(&v, bytes.data() + 2 * i, 2);
    const std::size_t c = i % channels;
    out[i] = offset[c] + scale[c] * v;
  }
  return out;
}

std::string encodeFloat32(const std::vector<double>& values) {
  std::vector<float> f(values.begin(), values.end());
  return base64Of(f);
}

std::string encodeBytes(const std::vector<std::uint8_t>& bytes) { return base64Of(bytes); }

std::string encodeInt32(const std::vector<std::int32_t>& values) { return base64Of(values); }

std::vector<std::uint8_t> decodeBase64(const std::string& text) {
  const std::vector<unsigned char> v = YAML::DecodeBase64(text);
  return {v.begin(), v.end()};
}

}  // namespace centaur::report
