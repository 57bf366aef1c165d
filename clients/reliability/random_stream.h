#pragma once
// Random numbers keyed by where they are used, not by the order they are drawn in: sample k
// of a run with seed s always gets the same variates, whichever thread, batch or replica
// evaluates it, so that parallel sampling reproduces its result for a seed at any concurrency.
// The stream is SplitMix64 (Steele, Lea & Flood 2014) started from a mix of (seed, key);
// normals by Box-Muller, identical on every standard library.
#include <cmath>
#include <cstdint>

namespace pfem::reliability {

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t key) : state_(mix(mix(seed) ^ (key + kGolden))) {}

  std::uint64_t next() { return mix(state_ += kGolden); }
  // Uniform in (0, 1): 53 random bits, never 0.
  double uniform() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    const double t = 2.0 * 3.14159265358979323846 * uniform();
    spare_ = r * std::sin(t);
    has_spare_ = true;
    return r * std::cos(t);
  }

 private:
  static constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ull;
  static std::uint64_t mix(std::uint64_t z) {  // SplitMix64's finaliser
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  std::uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace pfem::reliability
