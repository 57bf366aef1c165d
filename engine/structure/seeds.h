#pragma once
// Forward-mode seeds of the direct differentiation method (DDM): per parameter k, the
// derivative d(constant)/d(theta_k) of an object's constants (normally 0 or 1; any value
// is allowed, e.g. dA/dtheta = d db/dtheta + b dd/dtheta for a rectangle's area).
// T holds one derivative per constant and value-initialises to zero (double, or a struct
// with zero defaults). Parameters never seeded have zero seeds.
#include <stdexcept>
#include <string>
#include <vector>

namespace pfem::structure {

template <typename T>
class Seeds {
 public:
  void set(int k, const T& derivative) {
    if (k < 0) throw std::out_of_range("parameter index " + std::to_string(k) + " < 0");
    if (k >= static_cast<int>(seeds_.size())) seeds_.resize(k + 1, T{});
    seeds_[k] = derivative;
  }
  T operator[](int k) const {
    return static_cast<std::size_t>(k) < seeds_.size() ? seeds_[k] : T{};  // k < 0: huge
  }

 private:
  std::vector<T> seeds_;
};

}  // namespace pfem::structure
