#pragma once
// The BLAS runs in the thread that calls it. The engine links the system's libblas.so.3
// (Debian alternatives: OpenBLAS pthread, serial or openmp build, or the reference BLAS), and
// the factorisations call it (UMFPACK, CHOLMOD, the supernodal LDL^T's dgemm/dtrsm). Results
// must be bit-identical whatever runs beside them and whichever program runs them: OpenBLAS's
// own threads split large products differently (pfem run --sensitivity ddm on the yielding
// obstacle differs in the 3rd row with 2 OpenBLAS threads), and its serial build has no locks,
// so two engine runs calling it at once corrupt each other's products (identical DDM jobs on
// two server workers gave different Newton counts and sensitivities).
#include <string>

namespace pfem {

// Pins OpenBLAS to one thread (openblas_set_num_threads(1), looked up at run time; nothing to
// do for other BLAS libraries). Called by pfem::run; cheap after the first call.
void keep_blas_in_calling_thread();

// False when the loaded BLAS may not be called from two threads at once: OpenBLAS's sequential
// build without USE_LOCKING (Debian's libopenblas0-serial). The reference BLAS keeps no state.
bool blas_is_thread_safe();

// "OpenBLAS 0.3.21 DYNAMIC_ARCH NO_AFFINITY Haswell MAX_THREADS=64 (pthread)", or
// "not OpenBLAS" (for messages).
std::string blas_description();

}  // namespace pfem
