#include "sweep/mpi_session.hpp"

// The C API only: Open MPI's deprecated C++ bindings would need libmpi_cxx.
//
// Every call goes through the standard's profiling names (PMPI_...): Debian's sequential MUMPS (linked through
// Ipopt, and before libmpi) exports stub C functions MPI_Init, MPI_Comm_rank (always rank 0), MPI_Finalize (a
// no-op) and MPI_Wtime, and the dynamic linker resolves our calls of those names to the stubs (every rank then
// believed it was rank 0). The PMPI_ names exist in libmpi only. (MUMPS itself calls the Fortran names, mpi_bcast_
// etc., which libmpi does not define: no clash the other way.)
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <thread>

#include "common/error.hpp"

namespace centaur::sweep {

namespace {

constexpr std::chrono::microseconds kPoll{500};
constexpr std::size_t kChunk = std::size_t(1) << 30;  // MPI counts are int

void wait(MPI_Request& request) {
  for (;;) {
    int done = 0;
    PMPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace

bool MpiSession::launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"}) {
    if (std::getenv(v) != nullptr) return true;
  }
  return false;
}

MpiSession::MpiSession() {
  int provided = 0;
  if (PMPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    throw RuntimeError("MPI_Init_thread failed");
  }
  if (provided < MPI_THREAD_FUNNELED) {
    PMPI_Finalize();
    throw RuntimeError("the MPI library does not support MPI_THREAD_FUNNELED");
  }
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  PMPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  barrier();
  PMPI_Finalize();
}

void MpiSession::broadcast(std::string& bytes) const {
  std::uint64_t n = bytes.size();
  MPI_Request request;
  PMPI_Ibcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
  wait(request);
  bytes.resize(n);
  for (std::size_t at = 0; at < n; at += kChunk) {
    const int count = static_cast<int>(std::min<std::size_t>(kChunk, n - at));
    PMPI_Ibcast(bytes.data() + at, count, MPI_BYTE, 0, MPI_COMM_WORLD, &request);
    wait(request);
  }
}

void MpiSession::send(int to, int tag, const std::string& bytes) const {
  MPI_Request request;
  PMPI_Isend(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD, &request);
  wait(request);
}

bool MpiSession::poll(int tag, int& from) const {
  int flag = 0;
  MPI_Status status;
  PMPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &flag, &status);
  if (flag) from = status.MPI_SOURCE;
  return flag != 0;
}

std::string MpiSession::receive(int from, int tag) const {
  MPI_Status status;
  for (;;) {
    int flag = 0;
    PMPI_Iprobe(from, tag, MPI_COMM_WORLD, &flag, &status);
    if (flag) break;
    std::this_thread::sleep_for(kPoll);
  }
  int count = 0;
  PMPI_Get_count(&status, MPI_BYTE, &count);
  std::string bytes(static_cast<std::size_t>(count), '\0');
  PMPI_Recv(bytes.data(), count, MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}

void MpiSession::barrier() const {
  MPI_Request request;
  PMPI_Ibarrier(MPI_COMM_WORLD, &request);
  wait(request);
}

void MpiSession::abort(int code) const {
  PMPI_Abort(MPI_COMM_WORLD, code);
  std::abort();  // MPI_Abort does not return
}

}  // namespace centaur::sweep
