#pragma once
// The compact encoding of the report's time series (docs/report.md, "Encoding"): base64 text inside the page's
// JSON, decoded by the viewer into typed arrays.
//   int16 channels: rows x channels values, each channel quantised on its own range,
//                   value = offset[c] + scale[c] * int16, scale = (max - min) / 65534, so the error is at most
//                   scale / 2 (about 8e-6 x the channel's range; 5 um for a pelvis moving over 0.6 m);
//   float32:        plain IEEE single precision (plots, frame times, mesh vertices);
//   uint8 / int32:  contact flags, mesh faces.
// All little endian (what every browser's typed arrays use on x86 and ARM).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace centaur::report {

/// {"rows", "channels", "offset": [...], "scale": [...], "int16": base64} of row-major `values`
/// (values.size() = rows x channels). Non-finite values are stored as the channel's offset.
nlohmann::json encodeInt16Channels(const std::vector<double>& values, std::size_t channels);

/// The values an encodeInt16Channels object decodes to (what the viewer computes), row-major.
std::vector<double> decodeInt16Channels(const nlohmann::json& encoded);

/// base64 of the float32 values of `values` (NaN stays NaN: a gap in a plot).
std::string encodeFloat32(const std::vector<double>& values);
/// base64 of raw bytes.
std::string encodeBytes(const std::vector<std::uint8_t>& bytes);
std::string encodeInt32(const std::vector<std::int32_t>& values);

/// The bytes of a base64 text (for tests and decodeInt16Channels).
std::vector<std::uint8_t> decodeBase64(const std::string& text);

}  // namespace centaur::report
