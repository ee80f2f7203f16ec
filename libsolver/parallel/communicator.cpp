#include "communicator.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

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

double Communicator::min(double value) const {
  if (size_ == 1) return value;
  double low = 0;
  MPI_Allreduce(&value, &low, 1, MPI_DOUBLE, MPI_MIN, comm_of(handle_));
  return low;
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
double Communicator::min(double value) const { return value; }
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
