#include "common/excerpt.hpp"

#include <cstdio>

namespace centaur {

namespace {

void appendEscaped(std::string& out, unsigned char c, bool keep_newlines) {
  if (keep_newlines && (c == '\n' || c == '\t')) {
    out += static_cast<char>(c);
  } else if (c == '\n') {
    out += "\\n";
  } else if (c == '\t') {
    out += "\\t";
  } else if (c == '\r') {
    out += "\\r";
  } else if (c < 0x20 || c == 0x7f) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\x%02x", c);
    out += buf;
  } else {
    out += static_cast<char>(c);
  }
}

}  // namespace

std::string excerpt(std::string_view text, std::size_t max_bytes) {
  std::string out;
  const std::size_t n = text.size() <= max_bytes ? text.size() : max_bytes;
  out.reserve(n + 32);
  for (std::size_t i = 0; i < n; ++i) appendEscaped(out, static_cast<unsigned char>(text[i]), false);
  if (n < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) appendEscaped(out, static_cast<unsigned char>(c), true);
  return out;
}

}  // namespace centaur
