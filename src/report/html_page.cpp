#include "report/html_page.hpp"

#include "report/viewer_asset.hpp"

namespace centaur::report {

std::string htmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

namespace {

/// JSON that may sit inside <script type="application/json">: '<' only occurs in strings, where \u003c means the
/// same, so no "</script" or "<!--" can end or confuse the element.
std::string scriptSafeJson(const nlohmann::json& data) {
  const std::string raw = data.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);  // ASCII only
  std::string out;
  out.reserve(raw.size() + raw.size() / 64);
  for (const char c : raw) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string htmlPage(const std::string& title, const nlohmann::json& data) {
  const std::string json = scriptSafeJson(data);
  const std::string_view viewer = viewerScript();
  std::string page;
  page.reserve(json.size() + viewer.size() + 2048);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline'; "
          "style-src 'unsafe-inline'; img-src data: blob:\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<meta name=\"generator\" content=\"centaur report (viewer " + std::string(viewerScriptSha256().substr(0, 12)) +
          ")\">\n";
  page += "<title>" + htmlEscape(title) + "</title>\n</head>\n<body>\n";
  page += "<noscript>This report needs JavaScript and WebGL.</noscript>\n";
  page += "<script type=\"application/json\" id=\"centaur-report-data\">";
  page += json;
  page += "</script>\n<script>";
  page += viewer;
  page += "</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace centaur::report
