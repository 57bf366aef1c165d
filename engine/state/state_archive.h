#pragma once
// The state one time step hands to the next, saved to bytes or restored from them by the same
// code: each object's archive(StateArchive&) names its mutable members once, and the archive
// either appends their bytes (saving) or overwrites them from its bytes (restoring). A double
// goes as its 8 bytes, so that a run restarted from a checkpoint continues bit for bit
// (engine/analysis/checkpoint.h). Counts the model fixes (fibers, sections, elements) are saved
// too and checked on restoring, so that a state never lands in an object of another shape.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace pfem {

// A checkpoint that cannot be used: not one, truncated or corrupted, of another engine build,
// another model or other run options. The message says which.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateArchive {
 public:
  static StateArchive saving() { return StateArchive(true, {}); }
  static StateArchive restoring(std::string bytes) { return StateArchive(false, std::move(bytes)); }

  bool is_restoring() const { return !saving_; }
  // The bytes saved so far (saving), or those not yet read (restoring).
  std::string bytes() const { return saving_ ? bytes_ : bytes_.substr(pos_); }
  bool at_end() const { return pos_ == bytes_.size(); }

  // Numbers, enums and flags: their bytes.
  template <class T>
    requires std::is_arithmetic_v<T> || std::is_enum_v<T>
  void operator()(T& v) {
    raw(&v, sizeof v);
  }
  // Eigen matrices: the dimensions (checked when fixed), then the coefficients.
  template <class S, int R, int C, int O, int MR, int MC>
  void operator()(Eigen::Matrix<S, R, C, O, MR, MC>& m) {
    Eigen::Index rows = m.rows(), cols = m.cols();
    (*this)(rows), (*this)(cols);
    if (saving_) return raw(m.data(), sizeof(S) * m.size());
    if (rows < 0 || cols < 0 || (R != Eigen::Dynamic && rows != R) || (C != Eigen::Dynamic && cols != C))
      throw CheckpointError("checkpoint: a matrix of " + std::to_string(rows) + " x " + std::to_string(cols) +
                            " where the model has another shape");
    check_left(rows * cols, sizeof(S));
    m.resize(rows, cols);
    raw(m.data(), sizeof(S) * m.size());
  }
  // A compressed sparse matrix: dimensions, then its column starts, row indices and values.
  void operator()(Eigen::SparseMatrix<double>& m) {
    Eigen::Index rows = m.rows(), cols = m.cols(), nonzeros = m.nonZeros();
    (*this)(rows), (*this)(cols), (*this)(nonzeros);
    if (saving_) m.makeCompressed();
    else {
      if (rows < 0 || cols < 0 || nonzeros < 0) throw CheckpointError("checkpoint: a sparse matrix of negative size");
      check_left(cols + 1 + 3 * nonzeros, sizeof(int));  // ints and doubles of 3 ints each
      m.resize(rows, cols);
      m.resizeNonZeros(nonzeros);
    }
    raw(m.outerIndexPtr(), sizeof(int) * (cols + 1));
    raw(m.innerIndexPtr(), sizeof(int) * nonzeros);
    raw(m.valuePtr(), sizeof(double) * nonzeros);
  }
  void operator()(std::string& s) {
    std::uint64_t n = s.size();
    (*this)(n);
    if (!saving_) check_left(n, 1), s.resize(n);
    raw(s.data(), n);
  }
  // Vectors: the length, then each element as above.
  template <class T>
  void operator()(std::vector<T>& v) {
    std::uint64_t n = v.size();
    (*this)(n);
    if (!saving_) check_left(n, 1), v.resize(n);
    for (auto& x : v) (*this)(x);
  }
  template <class T, std::size_t N>
  void operator()(std::array<T, N>& v) {
    for (auto& x : v) (*this)(x);
  }
  template <class A, class B>
  void operator()(std::pair<A, B>& p) {
    (*this)(p.first), (*this)(p.second);
  }
  // A count the model fixes (what: "fibers of a section"): saved; on restoring it must equal
  // the object's own.
  void expect(std::uint64_t count, const char* what) {
    std::uint64_t saved = count;
    (*this)(saved);
    if (saved != count)
      throw CheckpointError(std::string("checkpoint: ") + std::to_string(saved) + " " + what + " where the model has " +
                            std::to_string(count));
  }

 private:
  StateArchive(bool saving, std::string bytes) : saving_(saving), bytes_(std::move(bytes)) {}
  void raw(void* p, std::size_t n) {
    if (saving_) return bytes_.append(static_cast<const char*>(p), n), void();
    if (n > bytes_.size() - pos_) throw CheckpointError("checkpoint: truncated");
    std::memcpy(p, bytes_.data() + pos_, n);
    pos_ += n;
  }
  // Before a count read from the file is allocated: at least `count` items of `size` bytes left.
  void check_left(std::uint64_t count, std::size_t size) const {
    if (count > (bytes_.size() - pos_) / size) throw CheckpointError("checkpoint: truncated");
  }

  bool saving_;
  std::string bytes_;
  std::size_t pos_ = 0;
};

}  // namespace pfem
