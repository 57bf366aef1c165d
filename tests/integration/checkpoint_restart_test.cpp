// Checkpoints and restarts (engine/analysis/checkpoint.h): a run stopped in the middle and
// continued from its checkpoint gives the same responses, sensitivities and counts as a run
// never stopped, bit for bit, for
//  - a fluid-only model (a coarse dam break), with and without the DDM;
//  - the yielding obstacle (a 0.2 m column leaning on the fiber-section beam, Fy = 12 kPa): its
//    base fibers yield before the checkpoint, so the plastic strains, back stresses and their
//    sensitivities must come back from it; with two parameters (GMRES sensitivity solves) and
//    with eight (UMFPACK's LU, whose symbolic analysis is carried over steps), and without DDM.
// And every checkpoint that cannot continue the run is refused, saying why.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/analysis/checkpoint.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

namespace fs = std::filesystem;

pfem::v1::Model example(const std::string& name) {
  return read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + name + ".json");
}

pfem::v1::Model coarse_dam_break() {
  auto model = example("dam-break");
  model.mutable_mesh()->set_h(0.01);
  model.mutable_analysis()->set_t_end(0.05);
  return model;
}

pfem::v1::Model yielding_obstacle() {
  auto model = example("dam-break-obstacle");
  auto* r = model.mutable_fluid_regions(0)->mutable_rectangle();
  r->mutable_min()->set_x(0.19), r->mutable_min()->set_y(0.0);
  r->mutable_max()->set_x(0.292), r->mutable_max()->set_y(0.2);
  for (auto& p : *model.mutable_parameters())
    if (p.name() == "Fy") p.set_value(1.2e4);
  model.mutable_analysis()->set_t_end(0.04);
  return model;
}

class CheckpointRestart : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pfem_checkpoint_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The run stopped (cancelled, as on SIGINT) after step `stop`, checkpointing every
  // `every` steps and when cancelled; then continued from the checkpoint.
  RunResult stopped_and_restarted(const pfem::v1::Model& model, RunOptions options, int stop, int every) {
    std::atomic<bool> cancel{false};
    options.cancel = &cancel;
    options.progress = [&](const Progress& p) {
      if (p.step == stop) cancel.store(true);
    };
    options.checkpoint_every = every;
    options.checkpoint_file = dir_ / "checkpoint.pfem";
    const RunResult first = run(model, options);
    EXPECT_EQ(first.summary.status, RunStatus::kCancelled) << first.summary.message;
    EXPECT_EQ(first.summary.steps, stop);
    const Checkpoint c = read_checkpoint(options.checkpoint_file);
    EXPECT_EQ(c.step, stop);
    int first_step = 0;  // of the restarted run: no replay from t = 0
    options.progress = [&](const Progress& p) {
      if (first_step == 0) first_step = p.step;
    };
    options.cancel = nullptr;
    options.restart_from = options.checkpoint_file;
    options.checkpoint_file = dir_ / "after-restart.pfem";
    RunResult restarted = run(model, options);
    EXPECT_EQ(first_step, stop + 1);
    return restarted;
  }

  fs::path dir_;
};

// Every value of a and b has the same bits.
void expect_bitwise_equal(const Histories& a, const Histories& b, const std::string& what) {
  ASSERT_EQ(a.columns, b.columns) << what;
  ASSERT_EQ(a.time.size(), b.time.size()) << what;
  ASSERT_GT(a.time.size(), 0u) << what;
  EXPECT_EQ(std::memcmp(a.time.data(), b.time.data(), a.time.size() * sizeof(double)), 0) << what << " times";
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    ASSERT_EQ(a.rows[i].size(), b.rows[i].size()) << what;
    for (std::size_t j = 0; j < a.rows[i].size(); ++j)
      ASSERT_EQ(std::memcmp(&a.rows[i][j], &b.rows[i][j], sizeof(double)), 0)
          << what << " " << a.columns[j] << " at t = " << a.time[i] << ": " << a.rows[i][j] << " vs " << b.rows[i][j];
  }
}

void expect_same_run(const RunResult& never_stopped, const RunResult& restarted) {
  ASSERT_EQ(never_stopped.summary.status, RunStatus::kCompleted) << never_stopped.summary.message;
  ASSERT_EQ(restarted.summary.status, RunStatus::kCompleted) << restarted.summary.message;
  expect_bitwise_equal(never_stopped.responses, restarted.responses, "responses");
  EXPECT_EQ(never_stopped.sensitivities.columns.empty(), restarted.sensitivities.columns.empty());
  if (!never_stopped.sensitivities.columns.empty())
    expect_bitwise_equal(never_stopped.sensitivities, restarted.sensitivities, "sensitivities");
  const RunSummary &a = never_stopped.summary, &b = restarted.summary;
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.newton_iterations, b.newton_iterations);
  EXPECT_EQ(a.factorizations, b.factorizations);
  EXPECT_EQ(a.substeps, b.substeps);
  EXPECT_EQ(a.removed_particles, b.removed_particles);
  EXPECT_EQ(a.inserted_particles, b.inserted_particles);
  EXPECT_EQ(a.particles, b.particles);
  EXPECT_EQ(a.max_elements, b.max_elements);
  EXPECT_EQ(a.fluid_area_initial, b.fluid_area_initial);
  EXPECT_EQ(a.fluid_area_final, b.fluid_area_final);
  EXPECT_EQ(a.fluid_area_max_drift, b.fluid_area_max_drift);
  EXPECT_EQ(a.warnings, b.warnings);
}

TEST_F(CheckpointRestart, FluidOnlyWithAndWithoutDdm) {
  const auto model = coarse_dam_break();
  for (const auto method : {SensitivityMethod::kNone, SensitivityMethod::kDdm}) {
    SCOPED_TRACE(method_name(method));
    RunOptions options;
    options.sensitivity = method;
    const RunResult never_stopped = run(model, options);
    EXPECT_GT(never_stopped.summary.inserted_particles + never_stopped.summary.removed_particles, 0);
    expect_same_run(never_stopped, stopped_and_restarted(model, options, 23, 10));
  }
}

// The incompressible formulation (engine/solve/fractional_step.h) hands nothing from step to
// step beyond the nodes, the mesh and the structure: its restart, with the approximate DDM, is
// bit-identical too (the yielding obstacle: the structure's history and its sensitivities).
TEST_F(CheckpointRestart, TheIncompressibleFormulationWithItsApproximateDdm) {
  auto model = yielding_obstacle();
  model.mutable_analysis()->set_formulation("incompressible");
  RunOptions options;
  options.sensitivity = SensitivityMethod::kDdm;
  options.params = {"E", "Fy"};
  expect_same_run(run(model, options), stopped_and_restarted(model, options, 13, 5));
}

// A piston wavemaker (tests/data/piston-tank.json to 0.4 s) with the DDM of its stroke and period:
// the paddle's place and velocity come from the motion at the restart's time.
TEST_F(CheckpointRestart, APistonWavemakerWithDdm) {
  auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/tests/data/piston-tank.json");
  model.mutable_analysis()->set_t_end(0.4);
  RunOptions options;
  options.sensitivity = SensitivityMethod::kDdm;
  expect_same_run(run(model, options), stopped_and_restarted(model, options, 37, 10));
}

TEST_F(CheckpointRestart, YieldingBeamWithGmresAndLuSensitivitiesAndWithout) {
  auto model = yielding_obstacle();
  for (const auto& [name, target] : {std::pair{"hardening", "material.steel.hardening_ratio"},
                                     std::pair{"depth", "section.obstacle.depth"}, std::pair{"rho_s", "beam.obstacle.rho"}}) {
    auto* p = model.add_parameters();
    p->set_name(name);
    p->add_targets(target);
  }
  const std::vector<std::vector<std::string>> cases = {
      {}, {"E", "Fy"}, {"E", "Fy", "rho_f", "mu", "kappa", "hardening", "depth", "rho_s"}};
  for (const auto& params : cases) {
    SCOPED_TRACE(std::to_string(params.size()) + " parameters");
    RunOptions options;
    options.sensitivity = params.empty() ? SensitivityMethod::kNone : SensitivityMethod::kDdm;
    options.params = params;
    const RunResult never_stopped = run(model, options);
    // The base fiber has yielded before the checkpoint (t = 0.025 s): its plastic state matters.
    const auto& r = never_stopped.responses;
    const int stress = r.column("base_fiber_stress");
    ASSERT_GE(stress, 0);
    double peak = 0.0;
    for (std::size_t i = 0; i < r.time.size() && r.time[i] <= 0.025 + 1e-12; ++i)
      peak = std::max(peak, std::abs(r.rows[i][stress]));
    EXPECT_GE(peak, 1.2e4);
    expect_same_run(never_stopped, stopped_and_restarted(model, options, 25, 25));
  }
}

class CheckpointRefused : public CheckpointRestart {
 protected:
  // A checkpoint of the coarse dam break with the DDM after step 10.
  void SetUp() override {
    CheckpointRestart::SetUp();
    options_.sensitivity = SensitivityMethod::kDdm;
    options_.params = {"mu"};
    options_.t_end = 0.011;
    options_.checkpoint_every = 10;
    options_.checkpoint_file = dir_ / "checkpoint.pfem";
    ASSERT_EQ(run(model_, options_).summary.status, RunStatus::kCompleted);
    options_.checkpoint_every = 0;
    options_.restart_from = options_.checkpoint_file;
    std::ifstream in(options_.restart_from, std::ios::binary);
    bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // The message of the CheckpointError that restarting throws.
  std::string refusal(const pfem::v1::Model& model, const RunOptions& options) {
    try {
      run(model, options);
    } catch (const CheckpointError& e) {
      return e.what();
    }
    return "(no error)";
  }
  // The message for a copy of the checkpoint changed by edit.
  template <class Edit>
  std::string refusal_of_changed(Edit edit) {
    std::string bytes = bytes_;
    edit(bytes);
    std::ofstream(dir_ / "changed.pfem", std::ios::binary) << bytes;
    RunOptions options = options_;
    options.restart_from = dir_ / "changed.pfem";
    return refusal(model_, options);
  }

  pfem::v1::Model model_ = coarse_dam_break();
  RunOptions options_;
  std::string bytes_;
};

TEST_F(CheckpointRefused, AnotherModelOrOtherOptions) {
  auto other = model_;
  other.mutable_fluid()->set_rho(998.0);
  EXPECT_EQ(refusal(other, options_), "restart: the model is not the checkpointed run's (modified: fluid.rho: 1000 -> 998)");
  RunOptions options = options_;
  options.dt = 0.0005;
  EXPECT_EQ(refusal(model_, options), "restart: dt is 5e-04 here but not set in the checkpointed run");
  options = options_;
  options.params = {"mu", "kappa"};
  EXPECT_EQ(refusal(model_, options), "restart: params is mu,kappa here but mu in the checkpointed run");
  options = options_;
  options.sensitivity = SensitivityMethod::kNone;
  options.params.clear();
  EXPECT_EQ(refusal(model_, options), "restart: sensitivity is none here but ddm in the checkpointed run");
}

TEST_F(CheckpointRefused, AnotherEngineBuildTruncatedOrCorrupted) {
  const std::string where = "checkpoint " + (dir_ / "changed.pfem").string() + ": ";
  // The build's id (64 hex digits) follows the first line and its length.
  const std::size_t id = bytes_.find('\n') + 1 + 8;
  ASSERT_EQ(bytes_.substr(id, 64), kEngineBuild);
  EXPECT_EQ(refusal_of_changed([&](std::string& b) { b[id] = b[id] == '0' ? '1' : '0'; }).rfind(
                where + "was written by another engine build", 0),
            0u);
  EXPECT_EQ(refusal_of_changed([](std::string& b) { b.resize(b.size() / 2); }),
            where + "is truncated or corrupted (its checksum does not match)");
  EXPECT_EQ(refusal_of_changed([](std::string& b) { b[b.size() / 2] ^= 1; }),
            where + "is truncated or corrupted (its checksum does not match)");
  EXPECT_EQ(refusal_of_changed([](std::string& b) { b = "{\"fluid\": {}}"; }), where + "is not a pfem checkpoint");
  EXPECT_EQ(refusal_of_changed([](std::string& b) { b.replace(0, b.find('\n'), "PFEM checkpoint 0"); }),
            where + "is of another checkpoint format (PFEM checkpoint 0; this engine reads format 1)");
}

TEST_F(CheckpointRefused, CheckpointsOfFiniteDifferenceRuns) {
  RunOptions options;
  options.sensitivity = SensitivityMethod::kFdm;
  options.checkpoint_every = 5;
  options.checkpoint_file = dir_ / "fdm.pfem";
  try {
    run(model_, options);
    FAIL() << "no error";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.errors().size(), 1u);
    EXPECT_EQ(e.errors()[0].path, "checkpoint_every");
  }
}

}  // namespace
}  // namespace pfem
