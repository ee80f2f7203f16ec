"""The Python module against the command line it wraps: the same case run from Python and from
`rbcflow run` gives the same diagnostics.csv (but for `seconds`); checkpoints written by one
continue in the other to 1e-12 (compare_runs); cases read and refuse as `rbcflow check` does;
read_run gives the run's tables and frames as numpy arrays."""

import os
import shutil
import subprocess
import unittest

import numpy as np

import rbcflow

EXE = os.environ["RBCFLOW_EXE"]
COMPARE = os.environ["RBCFLOW_COMPARE_RUNS"]
SOURCE = os.environ["RBCFLOW_SOURCE_DIR"]
RUNS = os.environ["RBCFLOW_TEST_DIR"]
CAPSULE = os.path.join(SOURCE, "data", "cases", "capsule_shear.toml")


def small_capsule():
    """capsule_shear.toml made small: N = 8, lambda = 5 (GMRES and its guesses carry state),
    6 steps of 0.01, a checkpoint every 3 steps, no renders."""
    case = rbcflow.load_case(CAPSULE)
    case["cells"]["order"] = 8
    case["cells"]["dealias"] = 2
    case["domain"]["viscosity_ratio"] = 5.0
    case["time"]["end"] = 0.06
    case["time"]["dt"] = 0.01
    case["output"]["every"] = 3
    case["output"]["checkpoint_every"] = 3
    case["output"]["render"] = False
    return case


def fresh(name):
    path = os.path.join(RUNS, name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(RUNS, exist_ok=True)
    return path


def cli(*args):
    return subprocess.run([EXE, *args], capture_output=True, text=True)


def diagnostics_without_seconds(path):
    with open(os.path.join(path, "diagnostics.csv")) as f:
        rows = [line.rstrip("\n").split(",") for line in f]
    k = rows[0].index("seconds")
    return [row[:k] + row[k + 1:] for row in rows]


class CaseFiles(unittest.TestCase):
    def test_a_case_reads_and_writes_like_nested_dicts(self):
        case = rbcflow.load_case(CAPSULE)
        self.assertEqual(case["cells"]["shape"], "sphere")
        case["time"]["end"] = 0.5
        again = rbcflow.Case.from_dict(case.to_dict())
        self.assertEqual(again["time"]["end"], 0.5)
        self.assertIn("end = 0.5", again.toml())

    def test_bad_keys_raise_case_error_naming_the_key(self):
        case = rbcflow.load_case(CAPSULE)
        case["cells"]["colour"] = "red"
        with self.assertRaises(rbcflow.CaseError) as e:
            case.check()
        self.assertIn("cells.colour: unknown key", str(e.exception))
        self.assertTrue(issubclass(rbcflow.CaseError, ValueError))
        with self.assertRaises(rbcflow.CaseError) as e:
            rbcflow.load_case(os.path.join(SOURCE, "tests", "apps", "bad_cases", "order_too_small.toml"))
        self.assertIn("cells.order: 3 is out of range", str(e.exception))

    def test_check_reports_what_rbcflow_check_reports(self):
        bad = os.path.join(SOURCE, "tests", "apps", "bad_cases", "outside_bifurcation.toml")
        with self.assertRaises(rbcflow.CaseError) as e:
            rbcflow.load_case(bad).check()
        cli_message = cli("check", bad).stderr.strip().split("\n")[-1]
        self.assertEqual("rbcflow check: " + str(e.exception), cli_message)


class Simulations(unittest.TestCase):
    def test_python_and_the_command_line_write_the_same_run(self):
        case = small_capsule()
        py_out, cli_out = fresh("same_python"), fresh("same_cli")
        sim = rbcflow.Simulation(case, out=py_out)
        self.assertEqual(sim.steps_done, 0)
        self.assertTrue(np.isnan(sim.cell_velocities()).all())
        sim.run()
        self.assertEqual(sim.steps_done, 6)
        self.assertAlmostEqual(sim.time, 0.06, places=12)
        case_file = os.path.join(RUNS, "same.toml")
        case.save(case_file)
        self.assertEqual(cli("run", case_file, "--out", cli_out, "--quiet").returncode, 0)
        self.assertEqual(diagnostics_without_seconds(py_out), diagnostics_without_seconds(cli_out))
        nodes = sim.cell_nodes(0)
        self.assertEqual(nodes.shape, (8 * 16, 3))
        self.assertEqual(sim.cell_centroids().shape, (1, 3))
        self.assertEqual(sim.cell_velocities().shape, (1, 3))
        self.assertTrue(np.isfinite(sim.cell_velocities()).all())
        with self.assertRaises(IndexError):
            sim.cell_nodes(1)
        d = sim.diagnostics()
        self.assertEqual(len(d["step"]), 6)
        np.testing.assert_array_equal(d["step"], np.arange(1, 7))

    def test_checkpoints_cross_between_python_and_the_command_line(self):
        case = small_capsule()
        case_file = os.path.join(RUNS, "cross.toml")
        case.save(case_file)
        whole = fresh("cross_whole")
        rbcflow.Simulation(case, out=whole).run()
        # Written by the command line, continued from Python.
        split = fresh("cross_cli_then_python")
        self.assertEqual(cli("run", case_file, "--out", split, "--steps", "3", "--quiet").returncode, 0)
        sim = rbcflow.Simulation.from_checkpoint(os.path.join(split, "checkpoints", "step_00000003.h5"), out=split)
        self.assertEqual(sim.steps_done, 3)
        sim.run()
        compared = subprocess.run([COMPARE, case_file, whole, split, "6", "1e-12"], capture_output=True, text=True)
        self.assertEqual(compared.returncode, 0, compared.stdout)
        # Written by Python, continued by the command line in place.
        other = fresh("cross_python_then_cli")
        sim = rbcflow.Simulation(case, out=other)
        sim.step(3)
        mine = os.path.join(other, "checkpoints", "step_00000003.h5")
        sim.checkpoint(mine)
        del sim
        result = cli("run", case_file, "--out", other, "--restart", mine, "--quiet")
        self.assertEqual(result.returncode, 0, result.stderr)
        compared = subprocess.run([COMPARE, case_file, whole, other, "6", "1e-12"], capture_output=True, text=True)
        self.assertEqual(compared.returncode, 0, compared.stdout)

    def test_an_earlier_run_is_kept_unless_overwrite(self):
        case = small_capsule()
        out = fresh("kept")
        sim = rbcflow.Simulation(case, out=out)
        sim.step(1)
        del sim
        with open(os.path.join(out, "diagnostics.csv")) as f:
            before = f.read()
        with self.assertRaises(rbcflow.CaseError) as e:
            rbcflow.Simulation(case, out=out)
        self.assertIn("holds an earlier run", str(e.exception))
        self.assertIn("overwrite=True", str(e.exception))
        with open(os.path.join(out, "diagnostics.csv")) as f:
            self.assertEqual(f.read(), before)
        rbcflow.Simulation(case, out=out, overwrite=True).step(2)
        self.assertEqual(len(rbcflow.read_run(out).diagnostics["step"]), 2)

    def test_a_failing_run_raises_run_error_with_the_command_lines_message(self):
        # tests/run/cases/blowup.toml: dt 8x the limit (37), unstable on purpose.
        case = rbcflow.load_case(os.path.join(SOURCE, "tests", "run", "cases", "blowup.toml"))
        with self.assertRaises(rbcflow.RunError) as e:
            rbcflow.Simulation(case, out=fresh("blowup")).run()
        self.assertRegex(str(e.exception), r"at step [0-9]+.*the last good checkpoint is .*step_[0-9]{8}\.h5")
        self.assertTrue(issubclass(rbcflow.RunError, RuntimeError))


class ReadingRuns(unittest.TestCase):
    def test_a_finished_run_reads_back_as_numpy_arrays(self):
        out = fresh("read")
        rbcflow.Simulation(small_capsule(), out=out).run()
        run = rbcflow.read_run(out)
        self.assertEqual(run.frames, [0, 3, 6])
        np.testing.assert_array_equal(run.diagnostics["step"], np.arange(1, 7))
        self.assertEqual(len(run.cells["taylor_deformation"]), 3)  # one cell, three frames
        frame = run.frame(6)
        self.assertEqual(frame["step"], 6)
        cells = frame["cells"]
        self.assertEqual(cells["points"].shape[1], 3)
        self.assertEqual(cells["triangles"].shape[1], 3)
        self.assertEqual(cells["velocity"].shape, cells["points"].shape)
        self.assertEqual(cells["tension"].shape, (cells["points"].shape[0],))
        self.assertTrue(np.issubdtype(cells["triangles"].dtype, np.integer))
        with self.assertRaises(rbcflow.CaseError):
            run.frame(5)


if __name__ == "__main__":
    unittest.main()
