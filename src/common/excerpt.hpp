#pragma once
// Text taken from an input (a YAML value, a key, an HDF5 attribute, a path) quoted in a message: bounded in
// length and with every control character escaped, so a hostile value can neither flood the terminal with
// megabytes nor inject lines or terminal escape sequences.
#include <cstddef>
#include <string>
#include <string_view>

namespace centaur {

/// Longest excerpt of an input quoted in a message, in bytes.
inline constexpr std::size_t kMaxExcerpt = 80;

/// `text` with control characters escaped (\n, \t, \xNN) and, when longer than `max_bytes`, cut after
/// `max_bytes` bytes with "... (<size> bytes)" appended.
std::string excerpt(std::string_view text, std::size_t max_bytes = kMaxExcerpt);

/// Escape control characters except newline and tab (a whole message printed to a terminal).
std::string printable(std::string_view text);

}  // namespace centaur
