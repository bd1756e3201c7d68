#include "middleware/middleware_config.hpp"

#include <cctype>
#include <filesystem>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"

namespace centaur::middleware {

const char* MiddlewareConfig::defaultsYaml() {
  return R"(middleware:                  # DDS (Cyclone DDS, ROS 2 wire conventions; docs/middleware.md)
  domain: 0                   # DDS domain id = ROS_DOMAIN_ID, [0, 232]
  interface: lo               # network interface; lo = loopback, unicast, no multicast; auto = CYCLONEDDS_URI
  peers: []                   # extra unicast discovery peers, e.g. [192.168.1.10]
  config_file: ""             # a Cyclone DDS XML file, used as is ("" = generated from interface and peers)
  namespace: /centaur         # ROS namespace of every topic
  realtime_priority: 0        # SCHED_FIFO priority of the node's threads, [0, 98]; 0 = normal scheduling
)";
}

namespace {

/// Names that go into XML unescaped: letters, digits and . _ - : (interfaces, hosts, addresses).
bool plainToken(const std::string& s) {
  if (s.empty() || s.size() > 253) return false;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && c != '.' && c != '_' && c != '-' && c != ':') return false;
  }
  return true;
}

/// A ROS namespace: "/" followed by segments of letters, digits and '_', separated by '/'.
bool rosNamespace(const std::string& s) {
  if (s.size() < 2 || s.size() > 200 || s.front() != '/' || s.back() == '/') return false;
  char prev = '/';
  for (std::size_t i = 1; i < s.size(); ++i) {
    const char c = s[i];
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (c == '/' && prev != '/');
    if (!ok) return false;
    prev = c;
  }
  return !std::isdigit(static_cast<unsigned char>(s[1]));
}

}  // namespace

void MiddlewareConfig::read(YamlReader& r) {
  r.get("domain", domain, 0, 232);
  r.get("realtime_priority", realtime_priority, 0, 98);
  r.get("interface", interface);
  if (interface != "auto" && !plainToken(interface)) {
    r.fail("interface", "must be a network interface name (letters, digits, . _ - :) or auto");
  }
  const YAML::Node list = r.raw("peers");
  if (list && !list.IsNull()) {
    if (!list.IsSequence() || list.size() > 64) r.fail("peers", "must be a list of at most 64 host names or addresses");
    peers.clear();
    for (const YAML::Node& p : list) {
      const std::string text = p.IsScalar() ? p.Scalar() : std::string();
      if (!plainToken(text)) r.fail("peers", "'" + text.substr(0, 64) + "' is not a host name or address");
      peers.push_back(text);
    }
  }
  r.get("config_file", config_file);
  if (!config_file.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(config_file, ec)) {
      r.fail("config_file", "'" + config_file + "' is not a readable file (a Cyclone DDS XML configuration)");
    }
  }
  r.get("namespace", ns);
  if (!rosNamespace(ns)) r.fail("namespace", "'" + ns.substr(0, 64) + "' is not a ROS namespace such as /centaur");
  r.finish();
}

std::string MiddlewareConfig::cycloneConfig() const {
  if (!config_file.empty()) return "file://" + std::filesystem::absolute(config_file).string();
  if (interface == "auto") return "";
  std::string xml = "<CycloneDDS><Domain id=\"any\"><General><Interfaces><NetworkInterface name=\"" + interface +
                    "\"/></Interfaces>";
  const bool loopback = interface == "lo";
  if (loopback) xml += "<AllowMulticast>false</AllowMulticast>";
  xml += "</General><Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>30"
         "</MaxAutoParticipantIndex>";
  if (loopback || !peers.empty()) {
    // Unicast discovery: an announcement sent before the peer's socket exists is lost, and Cyclone repeats it
    // only every SPDPInterval (30 s by default); two nodes started together would then wait that long.
    xml += "<SPDPInterval>1s</SPDPInterval>";
    xml += "<Peers>";
    if (loopback) xml += "<Peer address=\"127.0.0.1\"/>";
    for (const std::string& p : peers) xml += "<Peer address=\"" + p + "\"/>";
    xml += "</Peers>";
  }
  xml += "</Discovery></Domain></CycloneDDS>";
  return xml;
}

}  // namespace centaur::middleware
