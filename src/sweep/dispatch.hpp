#pragma once
// Who runs what: rank 0 (or the only process without MPI) hands the runs out dynamically - to its own pool of
// simulation threads and, under MPI, to every other rank that asks - and is the only one that receives the
// records (runs differ in length, so a static split would leave ranks idle). Protocol (MPI, byte messages of JSON):
//   worker -> rank 0 (tag kTagToRoot): {"results": [records...], "want": k}   k new runs wanted (0: none)
//   rank 0 -> worker (tag kTagToWorker): {"runs": [run indices]}             sent iff k > 0; fewer than k
//                                                                            means there are no more
// A worker asks for (threads + 1) runs at first, then for one per record it returns, so one run waits queued
// behind each thread and no thread idles for a round trip; it stops when rank 0 had no more and its own are done.
#include <cstddef>
#include <functional>
#include <vector>

#include "sweep/local_pool.hpp"
#include "sweep/mpi_session.hpp"
#include "sweep/run_record.hpp"

namespace centaur::sweep {

inline constexpr int kTagToRoot = 11;
inline constexpr int kTagToWorker = 12;

/// Rank 0: runs `todo` (in that order as workers free up) on `pool` and on the other ranks (if `mpi`); every batch
/// of records that arrived is given to `sink` on this thread. Returns when every run of `todo` came back and every
/// worker rank has stopped asking.
void dispatchRuns(const std::vector<std::size_t>& todo, LocalPool& pool, const MpiSession* mpi,
                  const std::function<void(std::vector<RunRecord>&)>& sink);

/// A worker rank: asks rank 0 for runs, runs them on `pool`, sends the records back, until rank 0 has no more.
void serveRuns(LocalPool& pool, const MpiSession& mpi);

}  // namespace centaur::sweep
