// Checkpoints through the stepper's own items: a written state reads back bit for bit into a
// fresh stepper of the same case; a checkpoint of the earlier layout (state version 1: no version
// item, the cells' reference shapes stored) still restarts; a newer version is refused by name.
#include "scenario/checkpoint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "scenario/scenario.h"

using namespace rbcflow;

namespace {

namespace fs = std::filesystem;

// A capsule in free-space shear (lambda = 5, so that GMRES and its guesses are used), N = 8.
const Case kCase = parse_case(
    "[domain]\nkind = \"free\"\nbackground_flow = { kind = \"shear\", rate = 1.0 }\nviscosity_ratio = 5.0\n"
    "[cells]\nshape = \"sphere\"\npositions = [[0.0, 0.0, 0.0]]\norder = 8\ndealias = 2\n"
    "perturbation = { l = 2, m = 0, amplitude = 0.05 }\n[cells.membrane]\nlaw = \"neo-hookean\"\n"
    "shear_modulus = 10.0\nbending_modulus = 0.0\n[time]\nend = 1.0\ndt = 0.01\ncollision_threshold = 0.0\n",
    "capsule.toml");

std::unique_ptr<CellStepper> fresh_stepper() {
  Scenario s = prepare_scenario(kCase);
  return make_stepper(s);
}

fs::path temp_file(const std::string& name) { return fs::temp_directory_path() / ("rbcflow_test_" + name); }

// Writes `w` to a file and reads it into a fresh stepper: the CheckpointError's message, or ""
// when it is accepted.
std::string refusal(const CheckpointWriter& w, const fs::path& file) {
  w.write(file);
  const auto stepper = fresh_stepper();
  std::string message;
  try {
    read_checkpoint(*stepper, kCase, file);
  } catch (const CheckpointError& e) {
    message = e.what();
  }
  fs::remove(file);
  return message;
}

void expect_same_state(const StepperState& a, const StepperState& b) {
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.steps, b.steps);
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  for (std::size_t k = 0; k < a.shapes.size(); ++k) EXPECT_EQ(a.shapes[k].values(), b.shapes[k].values());
  EXPECT_EQ(a.previous_velocity, b.previous_velocity);
  EXPECT_EQ(a.older_velocity, b.older_velocity);
  EXPECT_EQ(a.oldest_velocity, b.oldest_velocity);
  EXPECT_EQ(a.volume0, b.volume0);
  EXPECT_EQ(a.area0, b.area0);
}

}  // namespace

TEST(ScenarioCheckpoint, EveryItemOfTheStateReadsBackExactly) {
  const auto run_owner = fresh_stepper();
  CellStepper& run = *run_owner;
  for (int i = 0; i < 4; ++i) run.step();
  ASSERT_GT(run.state().oldest_velocity.size(), 0);  // every history item is in use
  const fs::path file = temp_file("checkpoint_roundtrip.h5");
  write_checkpoint(run, kCase, file);
  const auto restarted_owner = fresh_stepper();
  CellStepper& restarted = *restarted_owner;
  read_checkpoint(restarted, kCase, file);
  expect_same_state(run.state(), restarted.state());
  // And the continued runs agree bit for bit.
  run.step();
  restarted.step();
  expect_same_state(run.state(), restarted.state());
  // The checkpoint carries its case: the same physics (fingerprint) read back from it alone.
  EXPECT_EQ(case_fingerprint(case_of_checkpoint(file)), case_fingerprint(kCase));
  fs::remove(file);
}

TEST(ScenarioCheckpoint, TheEarlierLayoutWithoutAVersionStillRestarts) {
  const auto run_owner = fresh_stepper();
  CellStepper& run = *run_owner;
  for (int i = 0; i < 3; ++i) run.step();
  const StepperState s = run.state();
  // State version 1 as rbcflow wrote it before the stepper saved itself, field by field.
  CheckpointWriter w(case_fingerprint(kCase));
  w.put("time", s.time);
  w.put("steps", static_cast<long long>(s.steps));
  w.put("cells/count", 1LL);
  w.put("cells/0/coefficients", s.shapes[0].values());
  w.put("cells/0/reference", run.cells()[0].membrane->reference().coeffs().values());
  w.put("cells/initial_volume", Eigen::Map<const Eigen::VectorXd>(s.volume0.data(), 1));
  w.put("cells/initial_area", Eigen::Map<const Eigen::VectorXd>(s.area0.data(), 1));
  w.put("cells/previous_velocity", s.previous_velocity);
  w.put("cells/older_velocity", s.older_velocity);
  w.put("cells/oldest_velocity", s.oldest_velocity);
  const fs::path file = temp_file("checkpoint_state1.h5");
  w.write(file);
  const auto restarted_owner = fresh_stepper();
  CellStepper& restarted = *restarted_owner;
  read_checkpoint(restarted, kCase, file);
  expect_same_state(s, restarted.state());
  fs::remove(file);
}

TEST(ScenarioCheckpoint, ANewerStateVersionIsRefusedNamingIt) {
  CheckpointWriter w(case_fingerprint(kCase));
  w.put("state_version", 99LL);
  const std::string e = refusal(w, temp_file("checkpoint_state99.h5"));
  EXPECT_NE(e.find("checkpoint state version 99; this rbcflow reads state versions 1 to 3"), std::string::npos) << e;
}

TEST(ScenarioCheckpoint, ACheckpointOfAnotherCellCountIsRefusedNamingTheFile) {
  CheckpointWriter w(case_fingerprint(kCase));
  w.put("state_version", 2LL);
  w.put("time", 0.0);
  w.put("steps", 0LL);
  w.put("cells/count", 0LL);
  const fs::path file = temp_file("checkpoint_nocells.h5");
  const std::string e = refusal(w, file);
  EXPECT_NE(e.find(file.string() + ": restore: the state has 0 cells, the run 1"), std::string::npos) << e;
}

namespace {

// A red cell at rest in free-space shear at order `order`, time step `dt`; `shear_modulus` to
// make another case.
Case resting_cell(int order, double dt, double shear_modulus = 10.0) {
  return parse_case("[domain]\nkind = \"free\"\nbackground_flow = { kind = \"shear\", rate = 1.0 }\n"
                    "viscosity_ratio = 5.0\n[cells]\nshape = \"rbc\"\npositions = [[0.0, 0.0, 0.0]]\norder = " +
                        std::to_string(order) + "\ndealias = 2\n[cells.membrane]\nlaw = \"skalak\"\nshear_modulus = " +
                        std::to_string(shear_modulus) + "\ndilatation_modulus = 100.0\nbending_modulus = 0.0\n"
                        "[time]\nend = 1.0\ndt = " + std::to_string(dt) + "\ncollision_threshold = 0.0\n",
                    "resting.toml");
}

// A run of kCase three steps on (its velocity history in use), its checkpoint written to `file`.
std::unique_ptr<CellStepper> three_steps_checkpointed(const fs::path& file) {
  auto run = fresh_stepper();
  for (int i = 0; i < 3; ++i) run->step();
  write_checkpoint(*run, kCase, file);
  return run;
}

// A fresh stepper of `c` restarted from `file`.
std::unique_ptr<CellStepper> restarted_from(const Case& c, const fs::path& file) {
  Scenario s = prepare_scenario(c);
  auto stepper = make_stepper(s);
  read_checkpoint(*stepper, c, file);
  return stepper;
}

// The largest membrane traction on the cells of `s` (the background flow does not enter it).
double largest_traction(CellStepper& s) { return s.solve().traction.rowwise().norm().maxCoeff(); }

}  // namespace

// A restart may refine the cells (cells.order) and change the time step: the shapes are the
// checkpoint's coefficients zero-padded, the rest shapes those of the checkpoint's run
// resampled alike, so a cell at rest stays at rest to rounding: its membrane traction at
// order 12 is below 1e-10 of the shear modulus.
TEST(ScenarioCheckpoint, ARestartMayRefineTheCellsAndTheTimeStep) {
  const Case coarse = resting_cell(8, 0.01);
  Scenario s8 = prepare_scenario(coarse);
  const auto run = make_stepper(s8);
  const fs::path file = temp_file("checkpoint_refined.h5");
  write_checkpoint(*run, coarse, file);

  const Case fine = resting_cell(12, 0.005);
  EXPECT_EQ(as_run_of_checkpoint(fine, file).cells->order, 8);
  EXPECT_EQ(*as_run_of_checkpoint(fine, file).time.dt, 0.01);
  EXPECT_EQ(rediscretised_keys(coarse, fine), (std::vector<std::string>{"cells.order 8 -> 12", "time.dt 0.01 -> 0.005"}));
  EXPECT_TRUE(rediscretised_keys(coarse, coarse).empty());
  Scenario s12 = prepare_scenario(fine, std::nullopt, 8);
  const auto restarted = make_stepper(s12);
  read_checkpoint(*restarted, fine, file);
  const SHCoeffs padded = run->cells()[0].shape.coeffs().resampled(12);
  EXPECT_EQ(restarted->cells()[0].shape.coeffs().values(), padded.values());
  EXPECT_EQ(restarted->dt(), 0.005);
  const double shear_modulus = 10.0;
  EXPECT_LT(largest_traction(*restarted), 1e-10 * shear_modulus);

  // A step at order 12 goes on from there; another physics is still refused.
  EXPECT_NO_THROW(restarted->step());
  Scenario other_case = prepare_scenario(resting_cell(12, 0.005, 20.0), std::nullopt, 8);
  const auto other = make_stepper(other_case);
  try {
    read_checkpoint(*other, resting_cell(12, 0.005, 20.0), file);
    ADD_FAILURE() << "a checkpoint of another shear modulus was read";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("was written for another case"), std::string::npos) << e.what();
  }
  fs::remove(file);
}

// A restart may switch the contact repulsion on (or change it): the state, its history
// included, reads back bit for bit, and only the forces of the next steps differ.
TEST(ScenarioCheckpoint, ARestartMayChangeTheContactRepulsion) {
  const fs::path file = temp_file("checkpoint_contact.h5");
  const auto run_owner = three_steps_checkpointed(file);
  CellStepper& run = *run_owner;
  Case repelled = kCase;
  repelled.time.contact_range = 0.1;
  repelled.time.contact_strength = 50.0;
  EXPECT_TRUE(rediscretised_keys(as_run_of_checkpoint(repelled, file), repelled).empty());
  EXPECT_EQ(contact_keys(as_run_of_checkpoint(repelled, file), repelled),
            (std::vector<std::string>{"time.contact_range 0 -> 0.1", "time.contact_strength 0 -> 50"}));
  EXPECT_TRUE(contact_keys(kCase, kCase).empty());
  const auto restarted = restarted_from(repelled, file);
  expect_same_state(run.state(), restarted->state());
  const StepReport r = restarted->step();
  ASSERT_TRUE(r.contact.has_value());  // one cell alone: nothing within range
  EXPECT_EQ(r.contact->cells_in_range, 0);
  fs::remove(file);
}

// At the same order and another time step the shapes read back bit for bit and the velocity
// history is dropped (its first step is forward Euler, as a run's first is).
TEST(ScenarioCheckpoint, ARestartAtAnotherTimeStepStartsItsHistoryAfresh) {
  const fs::path file = temp_file("checkpoint_new_dt.h5");
  const auto run_owner = three_steps_checkpointed(file);
  CellStepper& run = *run_owner;
  Case halved = kCase;
  halved.time.dt = 0.005;
  const auto restarted = restarted_from(halved, file);
  EXPECT_EQ(restarted->state().shapes[0].values(), run.state().shapes[0].values());
  EXPECT_EQ(restarted->state().steps, 3);
  EXPECT_EQ(restarted->state().previous_velocity.size(), 0);
  EXPECT_EQ(restarted->state().oldest_velocity.size(), 0);
  EXPECT_EQ(restarted->dt(), 0.005);
  fs::remove(file);
}
