#pragma once
// The ranks that share a run (`mpirun -np P rbcflow run CASE.toml`). The state of a run (the
// cells' shapes, the wall force, the wall solve's GMRES vectors) is replicated on every rank;
// the work of the cells' operators, and of moving them, is split by the cells each rank owns
// (ownership.h; share_blocks.h makes what each computed whole again), and each
// product is summed over the ranks with sum(), or, where each rank keeps only its own rows (the
// GMRES vectors of (10) and (12), owned_rows.h), by sending each owner the rows of its
// part that are not zero (exchange). Every rank then takes the same decisions
// (GMRES iterations, collisions, output steps) from the same numbers.
//
// A Communicator that is not world() in an MPI launch is one rank: sum() does nothing, and
// code written against it runs exactly as the serial build does. The serial build (no MPI
// found, or RBCFLOW_MPI=OFF) compiles this file without MPI and world() is one rank.
#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

namespace rbcflow {

class Communicator {
 public:
  Communicator() = default;  // one rank
  // MPI_COMM_WORLD when MPI was initialised (MpiSession), else one rank.
  static Communicator world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  // Element-wise sum over the ranks, in place, with the same bits on every rank: reduced on
  // rank 0 and broadcast (an all-reduce may round differently on different ranks, and the
  // replicated GMRES must not diverge).
  void sum(std::span<double> values) const;
  template <class Derived>  // a dense Eigen matrix or vector of doubles
  void sum(Eigen::PlainObjectBase<Derived>& values) const {
    sum(std::span<double>(values.data(), static_cast<std::size_t>(values.size())));
  }
  long sum(long value) const;
  // The ranks' pieces side by side in rank order, on every rank: `all` (the sum of counts
  // values) gets counts[r] values from rank r, whose `mine` holds them (MPI_Allgatherv).
  void gather_pieces(std::span<const double> mine, std::span<double> all, std::span<const int> counts) const;
  // Each rank's own values for each other rank (MPI_Alltoallv): `out` holds send_counts[r]
  // values for rank r, rank after rank; `in` gets recv_counts[r] values from rank r, rank after
  // rank. A rank's values to itself are copied. The counts must agree with the other ranks'
  // (exchange_counts gives them).
  void exchange(std::span<const double> out, std::span<const int> send_counts, std::span<double> in,
                std::span<const int> recv_counts) const;
  void exchange(std::span<const int> out, std::span<const int> send_counts, std::span<int> in,
                std::span<const int> recv_counts) const;
  // How many values each rank will send this one, from how many this one sends each (MPI_Alltoall).
  std::vector<int> exchange_counts(std::span<const int> send_counts) const;
  // The smallest of the ranks' values, the same on every rank.
  double min(double value) const;
  // Element-wise largest of the ranks' values, in place, the same on every rank (exact).
  void max(std::span<double> values) const;
  // How many of the ranks share this rank's machine (its node: MPI_COMM_TYPE_SHARED).
  int ranks_on_this_machine() const;
  // Throws std::runtime_error naming `what` when the ranks hold different values of it (a
  // replicated quantity that diverged: the run cannot go on consistently).
  void check_same(long value, const std::string& what) const;
  // The MPI communicator as its Fortran handle (MPI_Comm_c2f), -1 for one rank: for the other
  // files of libsolver/parallel, which call MPI libraries themselves (slab_fft.h).
  int mpi_handle() const { return handle_; }

 private:
  int handle_ = -1;  // Fortran handle of the MPI communicator (MPI_Comm_c2f); -1: one rank
  int rank_ = 0, size_ = 1;
};

// Whether this build can run on several ranks (MPI found and RBCFLOW_MPI on).
bool built_with_mpi();
// The MPI library's own version line ("Open MPI v4.1.4, ..."), empty in a build without MPI.
std::string mpi_library_version();
// "2 ranks x 1 thread", "1 rank x 2 threads": what a run uses, for its start message.
std::string ranks_and_threads(int ranks, int threads);

// MPI for the life of a program launched by an MPI launcher (mpirun sets its environment); a
// program started on its own does not initialise MPI and runs on one rank, exactly as the
// serial build. Threads: funnelled (only the main thread calls MPI; OpenMP inside each rank).
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  // Ends every rank at once with `status` (one rank failed alone: the others would wait for it
  // in their next sum()). Does nothing on one rank.
  static void abort_all(int status);

 private:
  bool initialised_ = false;
};

}  // namespace rbcflow
