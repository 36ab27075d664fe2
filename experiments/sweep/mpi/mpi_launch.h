// MPI for `cmt sweep` under mpirun/srun (docs/sweeps.md "MPI"). The only place that talks to MPI: a plain
// `cmt` invocation never initializes it, so it needs no MPI runtime, no singleton init and no mpirun.
#pragma once

#include <string>

namespace cmt {

// True when the process was started by an MPI launcher: OpenMPI's mpirun (OMPI_COMM_WORLD_SIZE), a PMI or
// PMIx launcher such as Slurm's srun or MPICH's mpiexec (PMI_SIZE, PMIX_RANK).
bool launched_by_mpi();

// MPI_Init_thread on construction (MPI_THREAD_FUNNELED: rollout worker threads never call MPI),
// MPI_Finalize on destruction. One per process.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  int local_size() const { return local_size_; }  // ranks on this node (shared memory)
  void barrier() const;
  // Rank 0's `text` on every rank.
  std::string broadcast(const std::string& text) const;
  // The sum over all ranks, on every rank.
  long long sum(long long value) const;
  // Ends every rank of the job with `status` (an error on one rank must not leave the others waiting in a
  // collective call forever).
  [[noreturn]] void abort(int status) const;

 private:
  int rank_ = 0, size_ = 1, local_size_ = 1;
};

}  // namespace cmt
