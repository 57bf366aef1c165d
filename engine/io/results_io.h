#pragma once
// The run's files, as design.md fixes them: responses.csv (time,<recorder>...),
// sensitivities.csv (time,d<recorder>/d<param>...) when there are sensitivities, and
// summary.json. The same writer serves `pfem run` and `pfemctl result`.
#include <filesystem>
#include <string>

#include "engine/io/run_result.h"

namespace pfem {

void write_histories_csv(const Histories& histories, const std::filesystem::path& file);
std::string summary_json(const RunSummary& summary);
// Creates dir if needed and writes all of the result's files into it.
void write_results(const RunResult& result, const std::filesystem::path& dir);

}  // namespace pfem
