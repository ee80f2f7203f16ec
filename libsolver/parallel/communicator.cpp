#include "communicator.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#ifdef RBCFLOW_HAVE_MPI
#include <mpi.h>
#endif

namespace rbcflow {

#ifdef RBCFLOW_HAVE_MPI

namespace {

MPI_Comm comm_of(int handle) { return MPI_Comm_f2c(handle); }

bool mpi_running() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}

// Variables an MPI launcher sets for the programs it starts (OpenMPI, PMIx, MPICH/Hydra).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

Communicator Communicator::world() {
  Communicator c;
  if (!mpi_running()) return c;
  c.handle_ = static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD));
  MPI_Comm_rank(MPI_COMM_WORLD, &c.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &c.size_);
  return c;
}

void Communicator::sum(std::span<double> values) const {
  if (size_ == 1 || values.empty()) return;
  // MPI counts are int: reduce in pieces of at most 2^30 values.
  constexpr std::size_t kPiece = std::size_t{1} << 30;
  for (std::size_t begin = 0; begin < values.size(); begin += kPiece) {
    const int count = static_cast<int>(std::min(kPiece, values.size() - begin));
    double* data = values.data() + begin;
    MPI_Reduce(root() ? MPI_IN_PLACE : data, root() ? data : nullptr, count, MPI_DOUBLE, MPI_SUM, 0, comm_of(handle_));
    MPI_Bcast(data, count, MPI_DOUBLE, 0, comm_of(handle_));
  }
}

long Communicator::sum(long value) const {
  if (size_ == 1) return value;
  long total = 0;
  MPI_Allreduce(&value, &total, 1, MPI_LONG, MPI_SUM, comm_of(handle_));
  return total;
}

namespace {

// Offsets of consecutive pieces of these counts, checked against the ranks and the length.
std::vector<int> offsets_of(std::span<const int> counts, int ranks, std::size_t length) {
  if (static_cast<int>(counts.size()) != ranks) throw std::invalid_argument("Communicator: one count per rank");
  std::vector<int> offsets(counts.size(), 0);
  long sum = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = static_cast<int>(sum);
    sum += counts[r];
  }
  if (sum != static_cast<long>(length)) throw std::invalid_argument("Communicator: the counts do not match the lengths given");
  return offsets;
}

// offsets_of, and this rank's piece checked to hold `mine` values.
std::vector<int> piece_offsets(std::span<const int> counts, int ranks, std::size_t total, std::size_t mine, int rank) {
  std::vector<int> offsets = offsets_of(counts, ranks, total);
  if (static_cast<std::size_t>(counts[static_cast<std::size_t>(rank)]) != mine)
    throw std::invalid_argument("Communicator: the pieces do not match the lengths given");
  return offsets;
}

}  // namespace

void Communicator::gather_pieces(std::span<const double> mine, std::span<double> all, std::span<const int> counts) const {
  const std::vector<int> offsets = piece_offsets(counts, size_, all.size(), mine.size(), rank_);
  if (size_ == 1) {
    std::copy(mine.begin(), mine.end(), all.begin());
    return;
  }
  MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, comm_of(handle_));
}

namespace {

template <class T>
void exchange_values(std::span<const T> out, std::span<const int> send_counts, std::span<T> in,
                     std::span<const int> recv_counts, int ranks, MPI_Datatype type, MPI_Comm comm) {
  const std::vector<int> send_offsets = offsets_of(send_counts, ranks, out.size());
  const std::vector<int> recv_offsets = offsets_of(recv_counts, ranks, in.size());
  if (ranks == 1) {
    std::copy(out.begin(), out.end(), in.begin());
    return;
  }
  MPI_Alltoallv(out.data(), send_counts.data(), send_offsets.data(), type, in.data(), recv_counts.data(),
                recv_offsets.data(), type, comm);
}

}  // namespace

void Communicator::exchange(std::span<const double> out, std::span<const int> send_counts, std::span<double> in,
                            std::span<const int> recv_counts) const {
  exchange_values(out, send_counts, in, recv_counts, size_, MPI_DOUBLE, size_ == 1 ? MPI_COMM_SELF : comm_of(handle_));
}

void Communicator::exchange(std::span<const int> out, std::span<const int> send_counts, std::span<int> in,
                            std::span<const int> recv_counts) const {
  exchange_values(out, send_counts, in, recv_counts, size_, MPI_INT, size_ == 1 ? MPI_COMM_SELF : comm_of(handle_));
}

std::vector<int> Communicator::exchange_counts(std::span<const int> send_counts) const {
  if (static_cast<int>(send_counts.size()) != size_) throw std::invalid_argument("Communicator: one exchange count per rank");
  std::vector<int> recv(send_counts.size());
  if (size_ == 1) {
    recv[0] = send_counts[0];
    return recv;
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv.data(), 1, MPI_INT, comm_of(handle_));
  return recv;
}

double Communicator::min(double value) const {
  if (size_ == 1) return value;
  double low = 0;
  MPI_Allreduce(&value, &low, 1, MPI_DOUBLE, MPI_MIN, comm_of(handle_));
  return low;
}

void Communicator::max(std::span<double> values) const {
  if (size_ == 1 || values.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MAX, comm_of(handle_));
}

int Communicator::ranks_on_this_machine() const {
  if (size_ == 1) return 1;
  MPI_Comm machine;
  MPI_Comm_split_type(comm_of(handle_), MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &machine);
  int count = 1;
  MPI_Comm_size(machine, &count);
  MPI_Comm_free(&machine);
  return count;
}

void Communicator::check_same(long value, const std::string& what) const {
  if (size_ == 1) return;
  long low = 0, high = 0;
  MPI_Allreduce(&value, &low, 1, MPI_LONG, MPI_MIN, comm_of(handle_));
  MPI_Allreduce(&value, &high, 1, MPI_LONG, MPI_MAX, comm_of(handle_));
  if (low != high) {
    throw std::runtime_error("the ranks disagree on " + what + " (" + std::to_string(low) + " to " +
                             std::to_string(high) + "): their replicated states diverged");
  }
}

bool built_with_mpi() { return true; }

std::string mpi_library_version() {
  char version[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  MPI_Get_library_version(version, &length);
  std::string v(version, static_cast<std::size_t>(length));
  if (const std::size_t end = v.find('\n'); end != std::string::npos) v.resize(end);  // its first line
  return v;
}

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!launched_by_mpi() || mpi_running()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  initialised_ = true;
}

MpiSession::~MpiSession() {
  if (initialised_ && mpi_running()) MPI_Finalize();
}

void MpiSession::abort_all(int status) {
  if (mpi_running() && Communicator::world().size() > 1) MPI_Abort(MPI_COMM_WORLD, status);
}

#else  // one rank

Communicator Communicator::world() { return {}; }
void Communicator::sum(std::span<double>) const {}
long Communicator::sum(long value) const { return value; }
void Communicator::gather_pieces(std::span<const double> mine, std::span<double> all, std::span<const int>) const {
  if (all.size() != mine.size()) throw std::invalid_argument("Communicator: the pieces do not match the lengths given");
  std::copy(mine.begin(), mine.end(), all.begin());
}
void Communicator::exchange(std::span<const double> out, std::span<const int>, std::span<double> in,
                            std::span<const int>) const {
  if (in.size() != out.size()) throw std::invalid_argument("Communicator: the exchange counts do not match the lengths given");
  std::copy(out.begin(), out.end(), in.begin());
}
void Communicator::exchange(std::span<const int> out, std::span<const int>, std::span<int> in,
                            std::span<const int>) const {
  if (in.size() != out.size()) throw std::invalid_argument("Communicator: the exchange counts do not match the lengths given");
  std::copy(out.begin(), out.end(), in.begin());
}
std::vector<int> Communicator::exchange_counts(std::span<const int> send_counts) const {
  return {send_counts.begin(), send_counts.end()};
}
double Communicator::min(double value) const { return value; }
void Communicator::max(std::span<double>) const {}
int Communicator::ranks_on_this_machine() const { return 1; }
void Communicator::check_same(long, const std::string&) const {}
bool built_with_mpi() { return false; }
std::string mpi_library_version() { return {}; }
MpiSession::MpiSession(int&, char**&) {}
MpiSession::~MpiSession() = default;
void MpiSession::abort_all(int) {}

#endif

std::string ranks_and_threads(int ranks, int threads) {
  return std::to_string(ranks) + (ranks == 1 ? " rank x " : " ranks x ") + std::to_string(threads) +
         (threads == 1 ? " thread" : " threads");
}

}  // namespace rbcflow
