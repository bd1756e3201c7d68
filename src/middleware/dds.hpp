#pragma once
// A thin RAII layer over Cyclone DDS's C API for the nodes: one participant per process, typed writers and
// readers on the topics of topics.hpp, and a wait set. Messages are the idlc-generated C structs of
// src/middleware/idl (ROS 2 type names). Everything is created at start-up; write() and take() do not
// allocate on our side (Cyclone serialises into its own pooled buffers).
#include <dds/dds.h>

#include <cstdint>
#include <string>

#include "middleware/middleware_config.hpp"
#include "middleware/topics.hpp"

namespace centaur::middleware {

/// The DDS domain participant of this process (the domain is created with MiddlewareConfig::cycloneConfig()).
/// RuntimeError if DDS cannot start (e.g. the interface does not exist).
class Participant {
 public:
  explicit Participant(const MiddlewareConfig& config);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  dds_entity_t get() const { return participant_; }
  const MiddlewareConfig& config() const { return config_; }
  /// DDS topic name of a topic of the table under this namespace, e.g. "rt/centaur/joint_states".
  std::string ddsName(const TopicSpec& spec) const;
  std::string rosName(const TopicSpec& spec) const;
  /// The topic entity (created once per spec).
  dds_entity_t topic(const TopicSpec& spec);

 private:
  MiddlewareConfig config_;
  dds_entity_t domain_ = 0;
  dds_entity_t participant_ = 0;
};

/// The QoS of a topic of the table for a writer or a reader (reliability, history depth; see topics.hpp).
dds_qos_t* createQos(const TopicSpec& spec, bool reader);

/// A typed writer. `Msg` is the generated struct of spec.descriptor.
template <class Msg>
class Writer {
 public:
  Writer(Participant& p, const TopicSpec& spec);
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;
  /// false if DDS refused the sample (counted by the caller).
  bool write(const Msg& msg) { return dds_write(writer_, &msg) >= 0; }
  /// Number of matched readers.
  int matched() const;
  dds_entity_t get() const { return writer_; }

 private:
  dds_entity_t writer_ = 0;
};

/// A typed reader with a read condition (for a WaitSet).
template <class Msg>
class Reader {
 public:
  Reader(Participant& p, const TopicSpec& spec);
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  /// Takes every available valid sample (oldest first) and calls f(const Msg&, const dds_sample_info_t&) on
  /// each; returns how many were taken. Samples are loaned from Cyclone and returned before it returns.
  template <class F>
  int take(F&& f);
  dds_entity_t condition() const { return condition_; }
  dds_entity_t get() const { return reader_; }
  int matched() const;

 private:
  dds_entity_t reader_ = 0;
  dds_entity_t condition_ = 0;
};

/// Waits on the readers' conditions.
class WaitSet {
 public:
  explicit WaitSet(Participant& p);
  ~WaitSet();
  WaitSet(const WaitSet&) = delete;
  WaitSet& operator=(const WaitSet&) = delete;
  void attach(dds_entity_t condition);
  /// Blocks until a condition triggers or `timeout_ns` passes; returns the number triggered (0 on timeout).
  int wait(std::int64_t timeout_ns);

 private:
  dds_entity_t waitset_ = 0;
};

// ---- template definitions ----

namespace detail {
dds_entity_t createWriter(Participant& p, const TopicSpec& spec);
dds_entity_t createReader(Participant& p, const TopicSpec& spec);
int publicationMatched(dds_entity_t writer);
int subscriptionMatched(dds_entity_t reader);
}  // namespace detail

template <class Msg>
Writer<Msg>::Writer(Participant& p, const TopicSpec& spec) : writer_(detail::createWriter(p, spec)) {}

template <class Msg>
Writer<Msg>::~Writer() {
  if (writer_ > 0) dds_delete(writer_);
}

template <class Msg>
int Writer<Msg>::matched() const {
  return detail::publicationMatched(writer_);
}

template <class Msg>
Reader<Msg>::Reader(Participant& p, const TopicSpec& spec) : reader_(detail::createReader(p, spec)) {
  condition_ = dds_create_readcondition(reader_, DDS_ANY_STATE);
}

template <class Msg>
Reader<Msg>::~Reader() {
  if (reader_ > 0) dds_delete(reader_);  // deletes the read condition too
}

template <class Msg>
int Reader<Msg>::matched() const {
  return detail::subscriptionMatched(reader_);
}

template <class Msg>
template <class F>
int Reader<Msg>::take(F&& f) {
  constexpr int kBatch = 16;
  int total = 0;
  for (;;) {
    void* samples[kBatch] = {nullptr};
    dds_sample_info_t infos[kBatch];
    const dds_return_t n = dds_take(reader_, samples, infos, kBatch, kBatch);
    if (n <= 0) break;
    for (int i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      f(*static_cast<const Msg*>(samples[i]), infos[i]);
      ++total;
    }
    dds_return_loan(reader_, samples, n);
    if (n < kBatch) break;
  }
  return total;
}

}  // namespace centaur::middleware
