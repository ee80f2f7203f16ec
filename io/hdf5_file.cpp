#include "io/hdf5_file.h"

#include <algorithm>
#include <stdexcept>

#ifdef RBCFLOW_HAVE_PARALLEL_HDF5
#include <mpi.h>
#endif

namespace rbcflow::h5 {
namespace {

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("HDF5: " + what); }

hid_t checked(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

Id dataspace(const std::vector<hsize_t>& dims) {
  return Id(checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace"), H5Sclose);
}

// Whether `loc` is in a file shared by ranks (create_file with an MPI communicator).
bool shared_file(hid_t loc) {
#ifdef RBCFLOW_HAVE_PARALLEL_HDF5
  const Id file(checked(H5Iget_file_id(loc), "no file"), H5Fclose);
  const Id access(checked(H5Fget_access_plist(file.get()), "no access list"), H5Pclose);
  return H5Pget_driver(access.get()) == H5FD_MPIO;
#else
  (void)loc;
  return false;
#endif
}

// A shared file's data is written collectively: every rank calls H5Dwrite, selecting what it
// gives (possibly nothing).
Id collective_transfer() {
  Id transfer(checked(H5Pcreate(H5P_DATASET_XFER), "property list"), H5Pclose);
#ifdef RBCFLOW_HAVE_PARALLEL_HDF5
  check(H5Pset_dxpl_mpio(transfer.get(), H5FD_MPIO_COLLECTIVE), "collective transfer");
#endif
  return transfer;
}

template <typename T>
void write_rows(hid_t loc, const std::string& name, const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& m,
                hid_t file_type, hid_t memory_type, bool one_column_as_vector, RowBlock block) {
  const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = m;
  const bool part = block.total >= 0;  // m holds rows [begin, end) of the dataset only
  if (part && (block.begin < 0 || block.end - block.begin != m.rows() || block.end > block.total))
    fail("the rows " + std::to_string(block.begin) + ".." + std::to_string(block.end) + " of " +
         std::to_string(block.total) + " do not fit a part of " + std::to_string(m.rows()) + " rows of " + name);
  const long long n = part ? block.total : m.rows();
  std::vector<hsize_t> dims{static_cast<hsize_t>(n)};
  if (!(one_column_as_vector && m.cols() == 1)) dims.push_back(static_cast<hsize_t>(m.cols()));
  const Id space = dataspace(dims);
  const Id set(checked(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                     "cannot create dataset " + name),
               H5Dclose);
  if (n == 0 || m.cols() == 0) return;
  if (!shared_file(loc)) {
    if (part && m.rows() != n) fail("a part of the rows of " + name + " in a file of one process");
    check(H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data()), "cannot write " + name);
    return;
  }
  const long long begin = part ? block.begin : std::clamp(block.begin, 0LL, n);
  const long long end = part ? block.end : block.end < 0 ? n : std::clamp(block.end, begin, n);
  const long long offset = part ? 0 : begin;  // of the rank's first row in m
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = static_cast<hsize_t>(begin);
  count[0] = static_cast<hsize_t>(end - begin);
  const Id file_space(checked(H5Dget_space(set.get()), "no dataspace of " + name), H5Sclose);
  std::vector<hsize_t> memory_dims = count;
  memory_dims[0] = std::max<hsize_t>(count[0], 1);
  const Id memory_space = dataspace(memory_dims);
  if (count[0] > 0) {
    check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
          "cannot select rows of " + name);
  } else {
    H5Sselect_none(file_space.get());
    H5Sselect_none(memory_space.get());
  }
  const Id transfer = collective_transfer();
  const T none{};  // a buffer for a rank that writes no row
  check(H5Dwrite(set.get(), memory_type, memory_space.get(), file_space.get(), transfer.get(),
                 rows.size() > 0 ? rows.data() + offset * m.cols() : &none),
        "cannot write " + name);
}

// A scalar dataset's value, written by the ranks that hold it `mine` in a shared file.
void write_value(hid_t set, hid_t memory_type, const void* value, bool mine, const std::string& name) {
  if (!shared_file(set)) {
    check(H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value), "cannot write " + name);
    return;
  }
  const Id file_space(checked(H5Dget_space(set), "no dataspace of " + name), H5Sclose);
  const Id memory_space(checked(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  if (!mine) {
    H5Sselect_none(file_space.get());
    H5Sselect_none(memory_space.get());
  }
  const Id transfer = collective_transfer();
  check(H5Dwrite(set, memory_type, memory_space.get(), file_space.get(), transfer.get(), value), "cannot write " + name);
}

template <typename T>
Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> read_rows(hid_t loc, const std::string& name, hid_t memory_type) {
  const std::vector<hsize_t> dims = shape(loc, name);
  if (dims.empty() || dims.size() > 2) fail("dataset " + name + " is not a vector or a matrix");
  const Eigen::Index rows = static_cast<Eigen::Index>(dims[0]);
  const Eigen::Index cols = dims.size() == 2 ? static_cast<Eigen::Index>(dims[1]) : 1;
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(rows, cols);
  const Id set(checked(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "no dataset " + name), H5Dclose);
  if (m.size() > 0) {
    check(H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()), "cannot read " + name);
  }
  return m;
}

Id scalar_attribute(hid_t obj, const std::string& name, hid_t type) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  const Id space(checked(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  return Id(checked(H5Acreate2(obj, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                  "cannot create attribute " + name),
            H5Aclose);
}

Id open_attribute(hid_t obj, const std::string& name) {
  return Id(checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "no attribute " + name), H5Aclose);
}

}  // namespace

Id& Id::operator=(Id&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void Id::reset() {
  if (id_ >= 0 && close_) close_(id_);
  id_ = H5I_INVALID_HID;
}

QuietErrors::QuietErrors() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietErrors::~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

Id create_file(const std::filesystem::path& path) {
  return Id(checked(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "cannot create " + path.string()),
            H5Fclose);
}

bool parallel_io() {
#ifdef RBCFLOW_HAVE_PARALLEL_HDF5
  return true;
#else
  return false;
#endif
}

namespace {

// File access through MPI-IO by the ranks of a communicator.
Id shared_access(int mpi_handle) {
#ifdef RBCFLOW_HAVE_PARALLEL_HDF5
  Id access(checked(H5Pcreate(H5P_FILE_ACCESS), "property list"), H5Pclose);
  check(H5Pset_fapl_mpio(access.get(), MPI_Comm_f2c(mpi_handle), MPI_INFO_NULL), "MPI-IO file access");
  return access;
#else
  (void)mpi_handle;
  throw std::logic_error("HDF5: this build has no parallel HDF5: no file can be shared by ranks");
#endif
}

}  // namespace

Id create_file(const std::filesystem::path& path, int mpi_handle) {
  const Id access = shared_access(mpi_handle);
  return Id(checked(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), "cannot create " + path.string()),
            H5Fclose);
}

Id open_file(const std::filesystem::path& path, bool writable, int mpi_handle) {
  const Id access = shared_access(mpi_handle);
  return Id(checked(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, access.get()),
                    "cannot open " + path.string()),
            H5Fclose);
}

Id open_file(const std::filesystem::path& path, bool writable) {
  return Id(checked(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT),
                  "cannot open " + path.string()),
            H5Fclose);
}

void flush(hid_t file) { check(H5Fflush(file, H5F_SCOPE_GLOBAL), "cannot flush the file"); }

Id create_group(hid_t loc, const std::string& name) {
  const Id gcpl(checked(H5Pcreate(H5P_GROUP_CREATE), "property list"), H5Pclose);
  H5Pset_link_creation_order(gcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  return Id(checked(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), "cannot create group " + name),
            H5Gclose);
}

Id open_group(hid_t loc, const std::string& name) {
  return Id(checked(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), "no group " + name), H5Gclose);
}

bool exists(hid_t loc, const std::string& path) {
  std::string prefix;
  std::string::size_type start = 0;
  while (start <= path.size()) {
    const auto slash = path.find('/', start);
    prefix.append(prefix.empty() ? "" : "/").append(path.substr(start, slash - start));
    if (H5Lexists(loc, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    start = slash + 1;
  }
  return true;
}

std::vector<std::string> children(hid_t loc) {
  Id root;  // a file lists its root group
  const hid_t group = H5Iget_type(loc) == H5I_FILE ? (root = open_group(loc, "/")).get() : loc;
  H5G_info_t info;
  check(H5Gget_info(group, &info), "cannot list a group");
  // Groups made by create_group index their creation order; others list by name.
  const Id gcpl(H5Gget_create_plist(group), H5Pclose);
  unsigned flags = 0;
  H5Pget_link_creation_order(gcpl.get(), &flags);
  const H5_index_t index = (flags & H5P_CRT_ORDER_INDEXED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t n = H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (n < 0) fail("cannot list a group");
    std::string name(static_cast<std::size_t>(n), '\0');
    H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, name.data(), name.size() + 1, H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

void remove(hid_t loc, const std::string& name) {
  check(H5Ldelete(loc, name.c_str(), H5P_DEFAULT), "cannot remove " + name);
}

void soft_link(hid_t loc, const std::string& name, const std::string& target_path) {
  check(H5Lcreate_soft(target_path.c_str(), loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
        "cannot link " + name + " to " + target_path);
}

void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXd& m, bool one_column_as_vector,
                  RowBlock rows) {
  write_rows<double>(loc, name, m, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, one_column_as_vector, rows);
}

void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXi& m, RowBlock rows) {
  write_rows<int>(loc, name, m, H5T_STD_I32LE, H5T_NATIVE_INT, false, rows);
}

Eigen::MatrixXd read_matrix(hid_t loc, const std::string& name) {
  return read_rows<double>(loc, name, H5T_NATIVE_DOUBLE);
}

Eigen::MatrixXi read_int_matrix(hid_t loc, const std::string& name) {
  return read_rows<int>(loc, name, H5T_NATIVE_INT);
}

Eigen::MatrixXd read_matrix_rows(hid_t loc, const std::string& name, long long first, long long count) {
  const std::vector<hsize_t> dims = shape(loc, name);
  if (dims.empty() || dims.size() > 2) fail("dataset " + name + " is not a vector or a matrix");
  const long long rows = static_cast<long long>(dims[0]);
  if (first < 0 || count < 0 || first + count > rows)
    fail("rows " + std::to_string(first) + " to " + std::to_string(first + count) + " of " + name + ", which has " +
         std::to_string(rows));
  const Eigen::Index cols = dims.size() == 2 ? static_cast<Eigen::Index>(dims[1]) : 1;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(count, cols);
  if (m.size() == 0) return m;
  const Id set(checked(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "no dataset " + name), H5Dclose);
  const Id file_space(checked(H5Dget_space(set.get()), "no dataspace of " + name), H5Sclose);
  std::vector<hsize_t> start(dims.size(), 0), counts = dims;
  start[0] = static_cast<hsize_t>(first);
  counts[0] = static_cast<hsize_t>(count);
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, counts.data(), nullptr),
        "cannot select rows of " + name);
  const Id memory_space = dataspace(counts);
  check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT, m.data()),
        "cannot read " + name);
  return m;
}

std::vector<hsize_t> shape(hid_t loc, const std::string& name) {
  const Id set(checked(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "no dataset " + name), H5Dclose);
  const Id space(checked(H5Dget_space(set.get()), "no dataspace of " + name), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail("no dataspace of " + name);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

namespace {

Id scalar_dataset(hid_t loc, const std::string& name, hid_t type) {
  const Id space(checked(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  return Id(checked(H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    "cannot create dataset " + name),
            H5Dclose);
}

Id open_dataset(hid_t loc, const std::string& name) {
  return Id(checked(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "no dataset " + name), H5Dclose);
}

Id string_type(std::size_t size) {
  Id type(checked(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  H5Tset_size(type.get(), std::max<std::size_t>(size, 1));
  return type;
}

herr_t collect_dataset(hid_t, const char* name, const H5O_info_t* info, void* out) {
  if (info->type == H5O_TYPE_DATASET) static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

}  // namespace

void write_scalar(hid_t loc, const std::string& name, double value, bool mine) {
  const Id set = scalar_dataset(loc, name, H5T_IEEE_F64LE);
  write_value(set.get(), H5T_NATIVE_DOUBLE, &value, mine, name);
}

void write_scalar(hid_t loc, const std::string& name, long long value, bool mine) {
  const Id set = scalar_dataset(loc, name, H5T_STD_I64LE);
  write_value(set.get(), H5T_NATIVE_LLONG, &value, mine, name);
}

void write_scalar(hid_t loc, const std::string& name, const std::string& value, bool mine) {
  const Id type = string_type(value.size());
  const Id set = scalar_dataset(loc, name, type.get());
  std::string padded = value;
  padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
  write_value(set.get(), type.get(), padded.data(), mine, name);
}

double read_real(hid_t loc, const std::string& name) {
  const Id set = open_dataset(loc, name);
  double v = 0;
  check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v), "cannot read " + name);
  return v;
}

long long read_integer(hid_t loc, const std::string& name) {
  const Id set = open_dataset(loc, name);
  long long v = 0;
  check(H5Dread(set.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v), "cannot read " + name);
  return v;
}

std::string read_text(hid_t loc, const std::string& name) {
  const Id set = open_dataset(loc, name);
  const Id type(checked(H5Dget_type(set.get()), "no type of " + name), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    fail("dataset " + name + " is not a fixed-length string");
  }
  std::string v(H5Tget_size(type.get()), '\0');
  check(H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "cannot read " + name);
  return v.substr(0, v.find('\0'));
}

DatasetInfo dataset_info(hid_t loc, const std::string& name) {
  const Id set = open_dataset(loc, name);
  const Id type(checked(H5Dget_type(set.get()), "no type of " + name), H5Tclose);
  const Id space(checked(H5Dget_space(set.get()), "no dataspace of " + name), H5Sclose);
  DatasetInfo info;
  info.rank = H5Sget_simple_extent_ndims(space.get());
  switch (H5Tget_class(type.get())) {
    case H5T_FLOAT: info.kind = Kind::real; break;
    case H5T_INTEGER: info.kind = Kind::integer; break;
    case H5T_STRING: info.kind = Kind::text; break;
    default: info.kind = Kind::other;
  }
  return info;
}

std::vector<std::string> all_datasets(hid_t loc) {
  std::vector<std::string> names;
  check(H5Ovisit(loc, H5_INDEX_NAME, H5_ITER_INC, collect_dataset, &names), "cannot list the datasets");
  return names;
}

void create_parents(hid_t loc, const std::string& name) {
  for (auto slash = name.find('/'); slash != std::string::npos; slash = name.find('/', slash + 1)) {
    const std::string group = name.substr(0, slash);
    if (H5Lexists(loc, group.c_str(), H5P_DEFAULT) <= 0) create_group(loc, group);
  }
}

void write_attribute(hid_t obj, const std::string& name, double value) {
  const Id a = scalar_attribute(obj, name, H5T_IEEE_F64LE);
  check(H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value), "cannot write attribute " + name);
}

void write_attribute(hid_t obj, const std::string& name, long long value) {
  const Id a = scalar_attribute(obj, name, H5T_STD_I64LE);
  check(H5Awrite(a.get(), H5T_NATIVE_LLONG, &value), "cannot write attribute " + name);
}

void write_attribute(hid_t obj, const std::string& name, const std::string& value) {
  const Id type = string_type(value.size());
  const Id a = scalar_attribute(obj, name, type.get());
  std::string padded = value;
  padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
  check(H5Awrite(a.get(), type.get(), padded.data()), "cannot write attribute " + name);
}

bool has_attribute(hid_t obj, const std::string& name) { return H5Aexists(obj, name.c_str()) > 0; }

double read_double_attribute(hid_t obj, const std::string& name) {
  const Id a = open_attribute(obj, name);
  double v = 0;
  check(H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v), "cannot read attribute " + name);
  return v;
}

long long read_int_attribute(hid_t obj, const std::string& name) {
  const Id a = open_attribute(obj, name);
  const Id type(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_INTEGER) fail("attribute " + name + " is not an integer");
  long long v = 0;
  check(H5Aread(a.get(), H5T_NATIVE_LLONG, &v), "cannot read attribute " + name);
  return v;
}

std::string read_string_attribute(hid_t obj, const std::string& name) {
  const Id a = open_attribute(obj, name);
  const Id type(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    fail("attribute " + name + " is not a fixed-length string");
  }
  std::string v(H5Tget_size(type.get()), '\0');
  check(H5Aread(a.get(), type.get(), v.data()), "cannot read attribute " + name);
  return v.substr(0, v.find('\0'));
}

}  // namespace rbcflow::h5
