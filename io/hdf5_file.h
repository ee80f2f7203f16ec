#pragma once
// A thin C++ layer over the HDF5 C API for io/ (the XDMF writer and checkpoints): owned
// handles, row-major matrices, attributes. Errors throw std::runtime_error naming the object;
// HDF5's own error printing is off while a QuietErrors lives.
#include <hdf5.h>

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace rbcflow::h5 {

// An HDF5 identifier closed by its matching H5*close on destruction.
class Id {
 public:
  Id() = default;
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Id() { reset(); }
  Id(Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Id& operator=(Id&& o) noexcept;
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  hid_t get() const { return id_; }
  void reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

class QuietErrors {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

Id create_file(const std::filesystem::path& path);  // truncates
Id open_file(const std::filesystem::path& path, bool writable);

// A file created by the ranks of an MPI communicator together (`mpi_handle`, its Fortran
// handle: Communicator::mpi_handle() of libsolver/parallel), through HDF5's MPI-IO driver, in
// a build with parallel HDF5 (parallel_io(); else std::logic_error). Every rank then makes the
// same calls in the same order (groups, datasets and attributes are created collectively);
// the data of each dataset is written collectively, each rank giving its `rows` of it.
bool parallel_io();
Id create_file(const std::filesystem::path& path, int mpi_handle);
Id open_file(const std::filesystem::path& path, bool writable, int mpi_handle);

// The rows [begin, end) of a dataset that this rank writes into a file shared by ranks; the
// default, every row (the only choice in a file of one process).
struct RowBlock {
  long long begin = 0;
  long long end = -1;    // -1: to the last row
  long long total = -1;  // >= 0: the matrix written holds only rows [begin, end) of `total`
  static RowBlock none() { return {0, 0}; }
};
void flush(hid_t file);

// Groups track the creation order of their links, and children() lists them in that order.
Id create_group(hid_t loc, const std::string& name);
Id open_group(hid_t loc, const std::string& name);
bool exists(hid_t loc, const std::string& path);  // every component of a '/' path
std::vector<std::string> children(hid_t group_or_file);
void remove(hid_t loc, const std::string& name);
void soft_link(hid_t loc, const std::string& name, const std::string& target_path);

// Matrices are stored row-major (rows x cols); a matrix with one column is stored 1-D when
// `one_column_as_vector` (XDMF scalars). read_* accepts either.
// `rows`: what this rank writes of `m` (a file shared by ranks; each holds all of m).
void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXd& m, bool one_column_as_vector = false,
                  RowBlock rows = {});
void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXi& m, RowBlock rows = {});
Eigen::MatrixXd read_matrix(hid_t loc, const std::string& name);
Eigen::MatrixXi read_int_matrix(hid_t loc, const std::string& name);
// The rows [first, first + count) of a matrix of reals (a hyperslab: only those are read).
Eigen::MatrixXd read_matrix_rows(hid_t loc, const std::string& name, long long first, long long count);
// Dimensions of a dataset.
std::vector<hsize_t> shape(hid_t loc, const std::string& name);

// Scalar datasets; `mine`: whether this rank writes the value (a file shared by ranks).
void write_scalar(hid_t loc, const std::string& name, double value, bool mine = true);
void write_scalar(hid_t loc, const std::string& name, long long value, bool mine = true);
void write_scalar(hid_t loc, const std::string& name, const std::string& value, bool mine = true);
double read_real(hid_t loc, const std::string& name);
long long read_integer(hid_t loc, const std::string& name);
std::string read_text(hid_t loc, const std::string& name);

// What a dataset holds: its type class and rank (0 for a scalar).
enum class Kind { real, integer, text, other };
struct DatasetInfo {
  Kind kind = Kind::other;
  int rank = 0;
};
DatasetInfo dataset_info(hid_t loc, const std::string& name);
// Paths of all datasets below `loc`, depth first ("a/b/c").
std::vector<std::string> all_datasets(hid_t loc);
// Creates the groups of the parent path of `name` ("a/b" for "a/b/c") where missing.
void create_parents(hid_t loc, const std::string& name);

void write_attribute(hid_t obj, const std::string& name, double value);
void write_attribute(hid_t obj, const std::string& name, long long value);
void write_attribute(hid_t obj, const std::string& name, const std::string& value);
bool has_attribute(hid_t obj, const std::string& name);
double read_double_attribute(hid_t obj, const std::string& name);
long long read_int_attribute(hid_t obj, const std::string& name);
std::string read_string_attribute(hid_t obj, const std::string& name);

}  // namespace rbcflow::h5
