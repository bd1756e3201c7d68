#include "middleware/dds.hpp"

#include <pthread.h>
#include <sched.h>

#include <cstring>

#include "common/error.hpp"

namespace centaur::middleware {

namespace {
std::string ddsError(dds_return_t rc) { return std::string(dds_strretcode(rc)); }

/// The calling thread to SCHED_FIFO at `priority`; the threads it creates afterwards (Cyclone's receive and
/// event threads) inherit it. A 1 ms loop on a shared machine otherwise waits behind whatever else runs: measured
/// on loopback, the round-trip maximum drops from ~12 ms to < 1 ms (docs/benchmarks.md, "Middleware").
void useRealtimeScheduling(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (rc != 0) {
    throw InputError("middleware.realtime_priority: " + std::to_string(priority) + ": SCHED_FIFO refused (" +
                     std::strerror(rc) + "); it needs root, CAP_SYS_NICE or an rtprio limit (ulimit -r), or set 0");
  }
}
}  // namespace

Participant::Participant(const MiddlewareConfig& config) : config_(config) {
  if (config_.realtime_priority > 0) useRealtimeScheduling(config_.realtime_priority);
  const std::string cfg = config_.cycloneConfig();
  if (!cfg.empty()) {
    domain_ = dds_create_domain(static_cast<dds_domainid_t>(config_.domain), cfg.c_str());
    // A domain this process created already (e.g. two nodes in one test process) keeps its configuration.
    if (domain_ < 0 && domain_ != DDS_RETCODE_PRECONDITION_NOT_MET) {
      throw RuntimeError("DDS: cannot create domain " + std::to_string(config_.domain) + " on interface '" +
                         config_.interface + "': " + ddsError(domain_));
    }
    if (domain_ < 0) domain_ = 0;
  }
  participant_ = dds_create_participant(static_cast<dds_domainid_t>(config_.domain), nullptr, nullptr);
  if (participant_ < 0) {
    const dds_return_t rc = participant_;
    participant_ = 0;
    if (domain_ > 0) dds_delete(domain_);
    throw RuntimeError("DDS: cannot create a participant in domain " + std::to_string(config_.domain) + ": " +
                       ddsError(rc));
  }
}

Participant::~Participant() {
  if (participant_ > 0) dds_delete(participant_);
  if (domain_ > 0) dds_delete(domain_);
}

std::string Participant::rosName(const TopicSpec& spec) const { return config_.ns + "/" + spec.name; }

std::string Participant::ddsName(const TopicSpec& spec) const { return "rt" + rosName(spec); }

dds_entity_t Participant::topic(const TopicSpec& spec) {
  // Cyclone returns the existing topic entity for the same name and type within a participant.
  dds_qos_t* qos = createQos(spec, false);
  const dds_entity_t t = dds_create_topic(participant_, spec.descriptor, ddsName(spec).c_str(), qos, nullptr);
  dds_delete_qos(qos);
  if (t < 0) throw RuntimeError("DDS: cannot create topic " + ddsName(spec) + ": " + ddsError(t));
  return t;
}

dds_qos_t* createQos(const TopicSpec& spec, bool reader) {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, reader ? spec.reader_depth : spec.depth);
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  return qos;
}

namespace detail {

dds_entity_t createWriter(Participant& p, const TopicSpec& spec) {
  const dds_entity_t topic = p.topic(spec);
  dds_qos_t* qos = createQos(spec, false);
  const dds_entity_t w = dds_create_writer(p.get(), topic, qos, nullptr);
  dds_delete_qos(qos);
  if (w < 0) throw RuntimeError("DDS: cannot create a writer on " + p.ddsName(spec) + ": " + ddsError(w));
  return w;
}

dds_entity_t createReader(Participant& p, const TopicSpec& spec) {
  const dds_entity_t topic = p.topic(spec);
  dds_qos_t* qos = createQos(spec, true);
  const dds_entity_t r = dds_create_reader(p.get(), topic, qos, nullptr);
  dds_delete_qos(qos);
  if (r < 0) throw RuntimeError("DDS: cannot create a reader on " + p.ddsName(spec) + ": " + ddsError(r));
  return r;
}

int publicationMatched(dds_entity_t writer) {
  dds_publication_matched_status_t st;
  return dds_get_publication_matched_status(writer, &st) >= 0 ? static_cast<int>(st.current_count) : 0;
}

int subscriptionMatched(dds_entity_t reader) {
  dds_subscription_matched_status_t st;
  return dds_get_subscription_matched_status(reader, &st) >= 0 ? static_cast<int>(st.current_count) : 0;
}

}  // namespace detail

WaitSet::WaitSet(Participant& p) : waitset_(dds_create_waitset(p.get())) {
  if (waitset_ < 0) throw RuntimeError("DDS: cannot create a wait set: " + ddsError(waitset_));
}

WaitSet::~WaitSet() {
  if (waitset_ > 0) dds_delete(waitset_);
}

void WaitSet::attach(dds_entity_t condition) {
  const dds_return_t rc = dds_waitset_attach(waitset_, condition, condition);
  if (rc < 0) throw RuntimeError("DDS: cannot attach to the wait set: " + ddsError(rc));
}

int WaitSet::wait(std::int64_t timeout_ns) {
  const dds_return_t n = dds_waitset_wait(waitset_, nullptr, 0, timeout_ns);
  return n > 0 ? static_cast<int>(n) : 0;
}

}  // namespace centaur::middleware
