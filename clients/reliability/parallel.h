#pragma once
// Independent evaluations run side by side: the sampling methods, the chains of subset
// simulation, the 2P + 1 runs of a finite-difference gradient and the SORM gradients all hand
// their batch of tasks to parallel_for, with as many threads as the analysis' --concurrency
// (each thread makes one blocking call at a time: a simulation in-process or an Evaluate on
// some replica of the service).
#include <cstddef>
#include <functional>

namespace pfem::reliability {

// Runs task(i) for every i in [0, n) on up to `concurrency` threads (none is started when
// concurrency <= 1 or n <= 1: the tasks then run in order on the caller's thread). Each task
// writes only its own outputs, so the results do not depend on the concurrency. After a task
// throws, no new task starts; once the running ones finish, the exception of the lowest
// failed index is rethrown.
void parallel_for(std::size_t n, int concurrency, const std::function<void(std::size_t)>& task);

}  // namespace pfem::reliability
