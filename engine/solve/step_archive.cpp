// What one PFEM step hands to the next, saved for a checkpoint or restored from one (see
// UnifiedStep::archive). Everything else the step holds is rebuilt at every step.
#include "engine/solve/fluid_step.h"

namespace pfem {

void UnifiedStep::archive(StateArchive& a) {
  bubble_history_.archive(a);
  sensitivity_.archive(a);
}

}  // namespace pfem
