#include "io/checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <stdexcept>

#include "io/atomic_file.h"
#include "io/hdf5_file.h"

namespace rbcflow {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "rbcflow checkpoint";
constexpr long long kFormatVersion = 1;

// Data reaches the disk before the rename makes it the checkpoint.
void sync_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw std::runtime_error("cannot sync " + path.string());
  const int status = ::fsync(fd);
  ::close(fd);
  if (status != 0) throw std::runtime_error("cannot sync " + path.string());
}

}  // namespace

CheckpointWriter::CheckpointWriter(std::string case_fingerprint) : fingerprint_(std::move(case_fingerprint)) {}

void CheckpointWriter::add(const std::string& name, Item item) {
  if (name.empty() || name.front() == '/' || name.back() == '/' || name.find("//") != std::string::npos) {
    throw std::invalid_argument("checkpoint item name '" + name + "' is not a/b/c");
  }
  if (!items_.emplace(name, std::move(item)).second) {
    throw std::invalid_argument("checkpoint item " + name + " given twice");
  }
}

void CheckpointWriter::put_rows(const std::string& name, long long total_rows, long long first_row,
                                const Eigen::MatrixXd& rows) {
  if (first_row < 0 || first_row + rows.rows() > total_rows)
    throw std::invalid_argument("checkpoint item " + name + ": rows " + std::to_string(first_row) + ".." +
                                std::to_string(first_row + rows.rows()) + " of " + std::to_string(total_rows));
  add(name, Rows{rows, first_row, total_rows});
}

void CheckpointWriter::put(const std::string& name, long long value) { add(name, value); }
void CheckpointWriter::put(const std::string& name, double value) { add(name, value); }
void CheckpointWriter::put(const std::string& name, const std::string& value) { add(name, value); }

void CheckpointWriter::write_items(std::int64_t file, const Ranks* ranks) const {
  const hid_t f = static_cast<hid_t>(file);
  h5::write_attribute(f, "format", std::string(kFormat));
  h5::write_attribute(f, "format_version", kFormatVersion);
  h5::write_attribute(f, "case_fingerprint", fingerprint_);
  for (const auto& [name, item] : items_) {
    h5::create_parents(f, name);
    std::visit(
        [&, &n = name](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, Rows>) {
            if (!ranks && (v.first != 0 || v.rows.rows() != v.total))
              throw std::runtime_error("item " + n + ": a part of its rows in a file of one process");
            h5::write_matrix(f, n, v.rows, false,
                             ranks ? h5::RowBlock{v.first, v.first + v.rows.rows(), v.total} : h5::RowBlock{});
          } else if constexpr (std::is_same_v<T, Eigen::MatrixXd> || std::is_same_v<T, Eigen::MatrixXi>) {
            h5::RowBlock rows;
            if (ranks) {
              const auto [begin, end] = ranks->rows(n, v.rows());
              rows = {begin, end};
            }
            if constexpr (std::is_same_v<T, Eigen::MatrixXd>) {
              h5::write_matrix(f, n, v, false, rows);
            } else {
              h5::write_matrix(f, n, v, rows);
            }
          } else {
            bool mine = true;  // one row: written by the rank that writes row 0
            if (ranks) {
              const auto [begin, end] = ranks->rows(n, 1);
              mine = begin == 0 && end != 0;
            }
            h5::write_scalar(f, n, v, mine);
          }
        },
        item);
  }
}

void CheckpointWriter::write(const fs::path& file) const {
  const h5::QuietErrors quiet;
  try {
    write_atomically(file, [&](const fs::path& tmp) {
      {
        const h5::Id f = h5::create_file(tmp);
        write_items(f.get(), nullptr);
      }  // closed: everything is in the file
      sync_file(tmp);
    });
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write the checkpoint " + file.string() + ": " + e.what());
  }
}

bool CheckpointWriter::shared_by_ranks() { return h5::parallel_io(); }

void CheckpointWriter::write(const fs::path& file, const Ranks& ranks) const {
  const h5::QuietErrors quiet;
  const fs::path tmp = temporary_beside(file, ranks.tag);
  try {
    {
      const h5::Id f = h5::create_file(tmp, ranks.mpi_handle);
      write_items(f.get(), &ranks);
    }  // closed by every rank: everything is in the file
    if (ranks.rank == 0) {
      sync_file(tmp);
      fs::rename(tmp, file);
    }
  } catch (const std::exception& e) {
    if (ranks.rank == 0) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
    }
    throw std::runtime_error("cannot write the checkpoint " + file.string() + ": " + e.what());
  }
}

struct Checkpoint::OpenFile {
  h5::Id file;
};

Checkpoint Checkpoint::read(const fs::path& file, const std::string& case_fingerprint,
                            const std::function<bool(const std::string& name)>& by_rows) {
  return read_checked(file, &case_fingerprint, by_rows);
}

Checkpoint Checkpoint::read_any_case(const fs::path& file) { return read_checked(file, nullptr, {}); }

Checkpoint Checkpoint::read_checked(const fs::path& file, const std::string* case_fingerprint,
                                    const std::function<bool(const std::string& name)>& by_rows) {
  const std::string where = "checkpoint " + file.string();
  if (!fs::is_regular_file(file)) throw CheckpointError(where + ": no such file");
  const h5::QuietErrors quiet;
  if (H5Fis_hdf5(file.c_str()) <= 0) {
    throw CheckpointError(where + ": not an HDF5 file (truncated, or not a checkpoint)");
  }
  Checkpoint c;
  c.file_ = file;
  try {
    h5::Id f = h5::open_file(file, false);
    if (!h5::has_attribute(f.get(), "format") || h5::read_string_attribute(f.get(), "format") != kFormat) {
      throw CheckpointError(where + ": an HDF5 file, but not an rbcflow checkpoint");
    }
    const long long version = h5::read_int_attribute(f.get(), "format_version");
    if (version != kFormatVersion) {
      throw CheckpointError(where + ": format version " + std::to_string(version) + ", this rbcflow reads " +
                            std::to_string(kFormatVersion));
    }
    const std::string fingerprint = h5::read_string_attribute(f.get(), "case_fingerprint");
    if (case_fingerprint && fingerprint != *case_fingerprint) {
      throw CheckpointError(where + " was written for another case (case fingerprint " + fingerprint +
                            ", this case " + *case_fingerprint +
                            "); restart with the case.toml of its output directory, changed at most in the discretisation "
                            "(cells.order, cells.dealias, time.dt, time.dt_safety)");
    }
    for (const std::string& name : h5::all_datasets(f.get())) {
      const h5::DatasetInfo info = h5::dataset_info(f.get(), name);
      if (info.kind == h5::Kind::real && info.rank == 0) {
        c.items_.emplace(name, h5::read_real(f.get(), name));
      } else if (info.kind == h5::Kind::integer && info.rank == 0) {
        c.items_.emplace(name, h5::read_integer(f.get(), name));
      } else if (info.kind == h5::Kind::text) {
        c.items_.emplace(name, h5::read_text(f.get(), name));
      } else if (info.kind == h5::Kind::real && by_rows && by_rows(name)) {
        const std::vector<hsize_t> dims = h5::shape(f.get(), name);
        c.items_.emplace(name, ByRows{static_cast<long long>(dims[0]),
                                      dims.size() == 2 ? static_cast<long long>(dims[1]) : 1LL});
      } else if (info.kind == h5::Kind::real) {
        c.items_.emplace(name, h5::read_matrix(f.get(), name));
      } else if (info.kind == h5::Kind::integer) {
        c.items_.emplace(name, h5::read_int_matrix(f.get(), name));
      } else {
        throw CheckpointError(where + ": item " + name + " has an unknown type");
      }
    }
    if (by_rows) c.open_ = std::make_shared<const OpenFile>(OpenFile{std::move(f)});
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw CheckpointError(where + ": damaged or truncated (" + e.what() + ")");
  }
  return c;
}

std::vector<std::string> Checkpoint::names() const {
  std::vector<std::string> n;
  for (const auto& [name, item] : items_) n.push_back(name);
  return n;
}

template <typename T>
const T& Checkpoint::get(const std::string& name, const char* what) const {
  const auto it = items_.find(name);
  if (it == items_.end()) throw CheckpointError("checkpoint " + file_.string() + " has no item " + name);
  if (!std::holds_alternative<T>(it->second)) {
    throw CheckpointError("checkpoint " + file_.string() + ": item " + name + " is not " + what);
  }
  return std::get<T>(it->second);
}

const Eigen::MatrixXd& Checkpoint::matrix(const std::string& name) const {
  const auto it = items_.find(name);
  if (it != items_.end() && std::holds_alternative<ByRows>(it->second))
    throw CheckpointError("checkpoint " + file_.string() + ": item " + name + " is read by rows (rows())");
  return get<Eigen::MatrixXd>(name, "a matrix of reals");
}
const Eigen::MatrixXi& Checkpoint::int_matrix(const std::string& name) const {
  return get<Eigen::MatrixXi>(name, "a matrix of integers");
}
std::pair<long long, long long> Checkpoint::matrix_size(const std::string& name) const {
  const auto it = items_.find(name);
  if (it != items_.end()) {
    if (const ByRows* left = std::get_if<ByRows>(&it->second)) return {left->rows, left->cols};
  }
  const Eigen::MatrixXd& m = matrix(name);
  return {m.rows(), m.cols()};
}

Eigen::MatrixXd Checkpoint::rows(const std::string& name, long long first, long long count) const {
  const auto [rows, cols] = matrix_size(name);
  if (first < 0 || count < 0 || first + count > rows) {
    throw CheckpointError("checkpoint " + file_.string() + ": item " + name + " has " + std::to_string(rows) +
                          " rows, not rows " + std::to_string(first) + " to " + std::to_string(first + count));
  }
  const auto it = items_.find(name);
  if (!std::holds_alternative<ByRows>(it->second)) return std::get<Eigen::MatrixXd>(it->second).middleRows(first, count);
  const h5::QuietErrors quiet;
  try {
    return h5::read_matrix_rows(open_->file.get(), name, first, count);
  } catch (const std::runtime_error& e) {
    throw CheckpointError("checkpoint " + file_.string() + ": damaged or truncated (" + e.what() + ")");
  }
}

long long Checkpoint::integer(const std::string& name) const { return get<long long>(name, "an integer"); }
double Checkpoint::real(const std::string& name) const { return get<double>(name, "a real"); }
const std::string& Checkpoint::text(const std::string& name) const { return get<std::string>(name, "a string"); }

}  // namespace rbcflow
