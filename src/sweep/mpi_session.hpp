#pragma once
// Open MPI for the sweep, in the normal `centaur` binary: MPI is initialised only when the process was started by
// an MPI launcher (mpirun/mpiexec: OMPI_COMM_WORLD_SIZE; Slurm's srun: PMIX_RANK or PMI_RANK), so a plain
// `centaur sweep` (and every other command) never pays MPI's start-up. Only the main thread calls MPI
// (MPI_THREAD_FUNNELED). Every wait polls with short sleeps instead of blocking in MPI: Open MPI's blocking
// calls spin, which would steal a core from the simulations (e.g. while rank 0 plans the database).
// Messages are byte strings (JSON text or file contents).
#include <string>

namespace centaur::sweep {

class MpiSession {
 public:
  /// True if an MPI launcher started this process.
  static bool launched();

  /// MPI_Init_thread; RuntimeError if MPI cannot start or does not give MPI_THREAD_FUNNELED.
  MpiSession();
  /// MPI_Finalize (after a barrier that polls).
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  /// Rank 0's `bytes` to every rank (the others' `bytes` is replaced).
  void broadcast(std::string& bytes) const;
  void send(int to, int tag, const std::string& bytes) const;
  /// If a message with `tag` from any rank is waiting: true, its source in `from`.
  bool poll(int tag, int& from) const;
  /// Receives the waiting (or next) message with `tag` from `from`.
  std::string receive(int from, int tag) const;
  /// Every rank arrives (polls while waiting).
  void barrier() const;
  /// Ends every rank of the job with `code` (after an unrecoverable error on one of them).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool finalized_ = false;
};

}  // namespace centaur::sweep
