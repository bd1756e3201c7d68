#pragma once
// The self-contained report page: one HTML file with the data and the viewer inline. A Content-Security-Policy
// forbids every network request (fetch, images, fonts, sub-resources): the page works from file:// with no
// network and no server, and cannot leak anything.
#include <string>

#include <nlohmann/json.hpp>

namespace centaur::report {

/// The page for `data` (the report JSON, docs/report.md) titled `title`.
std::string htmlPage(const std::string& title, const nlohmann::json& data);

/// `text` with &, <, >, " escaped for HTML.
std::string htmlEscape(const std::string& text);

}  // namespace centaur::report
