#include "engine/analysis/blas_threads.h"

#include <dlfcn.h>

#include <mutex>

namespace pfem {
namespace {

// OpenBLAS's controls, when the loaded BLAS is OpenBLAS (the Fortran BLAS interface has none).
template <typename Function>
Function* openblas_function(const char* name) {
  return reinterpret_cast<Function*>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

void keep_blas_in_calling_thread() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (auto* set = openblas_function<void(int)>("openblas_set_num_threads")) set(1);
  });
}

bool blas_is_thread_safe() {
  auto* parallel = openblas_function<int()>("openblas_get_parallel");
  if (!parallel || parallel() != 0) return true;  // not OpenBLAS, or a threaded build (locks)
  // A sequential build is safe only with USE_LOCKING, which OpenBLAS >= 0.3.27 lists here.
  auto* config = openblas_function<char*()>("openblas_get_config");
  return config && std::string(config()).find("USE_LOCKING") != std::string::npos;
}

std::string blas_description() {
  auto* config = openblas_function<char*()>("openblas_get_config");
  if (!config) return "not OpenBLAS";
  static constexpr const char* kModes[] = {"sequential", "pthread", "openmp"};
  auto* parallel = openblas_function<int()>("openblas_get_parallel");
  const int mode = parallel ? parallel() : -1;
  return std::string(config()) + " (" + (mode >= 0 && mode <= 2 ? kModes[mode] : "?") + ")";
}

}  // namespace pfem
