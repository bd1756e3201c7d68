#pragma once
// Where the nodes talk: the DDS domain, the network interface, unicast peers and the topic namespace
// (YAML section `middleware:`, documented defaults below and in docs/middleware.md).
//
// Cyclone DDS configuration, in order of precedence:
//   1. `config_file` (a Cyclone DDS XML file, used as is);
//   2. the environment variable CYCLONEDDS_URI, when `config_file` is "" and `interface` is left at "auto";
//   3. generated from `interface` and `peers`: on "lo" (the default) unicast discovery with the peer
//      127.0.0.1 and multicast off, so two processes on one machine find each other without multicast;
//      on another interface (e.g. "eth0") Cyclone's default multicast discovery on it, plus `peers`.
#include <string>
#include <vector>

namespace centaur {
class YamlReader;
}

namespace centaur::middleware {

struct MiddlewareConfig {
  int domain = 0;                    ///< DDS domain id (ROS_DOMAIN_ID), [0, 232]
  std::string interface = "lo";      ///< network interface name, or "auto" (CYCLONEDDS_URI or Cyclone's choice)
  std::vector<std::string> peers;    ///< extra unicast discovery peers (host names or addresses)
  std::string config_file;           ///< Cyclone DDS XML file; "" = generated (see above)
  std::string ns = "/centaur";       ///< ROS namespace of every topic ("/centaur/joint_states")
  /// SCHED_FIFO priority of the node's threads (its loop and Cyclone's receive threads), [1, 98]; 0 = the normal
  /// time-sharing scheduler. Needs root, CAP_SYS_NICE or an rtprio limit (`ulimit -r`).
  int realtime_priority = 0;

  /// The `middleware:` section with its documented defaults (YAML text, root key `middleware:`).
  static const char* defaultsYaml();
  /// Read the section strictly (finish() included). InputError naming the key and range.
  void read(YamlReader& r);

  /// The Cyclone DDS configuration to create the domain with: XML text, a file:// URI, or "" (Cyclone's
  /// own: the environment's CYCLONEDDS_URI or its defaults).
  std::string cycloneConfig() const;
};

}  // namespace centaur::middleware
