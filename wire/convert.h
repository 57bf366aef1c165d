#pragma once
// Conversions between the engine's run types (engine/analysis/run.h, engine/io/run_result.h)
// and the wire (pfem.v1): results, summaries, histories, progress, sensitivity methods. Shared
// by the server, pfemctl and the tests. Header-only engine types: linking the engine is not
// needed for these.
#include "engine/analysis/run.h"
#include "pfem/v1/service.pb.h"

namespace pfem::wire {

pfem::v1::Histories to_proto(const Histories& histories);
Histories from_proto(const pfem::v1::Histories& histories);
pfem::v1::Summary to_proto(const RunSummary& summary);
RunSummary from_proto(const pfem::v1::Summary& summary);
pfem::v1::Result to_proto(const RunResult& result);
RunResult from_proto(const pfem::v1::Result& result);
pfem::v1::Progress to_proto(const Progress& progress);

SensitivityMethod from_proto(pfem::v1::SensitivityMethod method, SensitivityMethod fallback);
pfem::v1::SensitivityMethod to_proto(SensitivityMethod method);

}  // namespace pfem::wire
