"""A capsule in shear flow at three viscosity ratios: the Taylor deformation against time.

    PYTHONPATH=build/python python3 examples/python/viscosity_sweep.py [OUTDIR]

Runs data/cases/capsule_shear.toml (a neo-Hookean capsule, Ca = 0.1, N = 16) to t = 2 at
lambda = 0.2, 1 and 5, each into OUTDIR/lambda_<value> (default out/viscosity_sweep), and plots
the deformation of each run, read back with rbcflow.read_run, into OUTDIR/taylor.png.
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt

import rbcflow

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.join(HERE, "..", "..", "data", "cases", "capsule_shear.toml")


def main(out):
    plt.figure(figsize=(6, 4))
    for ratio in (0.2, 1.0, 5.0):
        case = rbcflow.load_case(CASE)
        case["domain"]["viscosity_ratio"] = ratio
        case["time"]["end"] = 2.0
        case["output"]["every"] = 10
        case["output"]["render"] = False
        run_dir = os.path.join(out, "lambda_%g" % ratio)
        sim = rbcflow.Simulation(case, out=run_dir, overwrite=True)
        sim.run()
        cells = rbcflow.read_run(run_dir).cells
        plt.plot(cells["time"], cells["taylor_deformation"], label="lambda = %g" % ratio)
        print("lambda = %g: D = %.4f at t = %g" % (ratio, cells["taylor_deformation"][-1], sim.time))
    plt.xlabel("time (shear rate^-1)")
    plt.ylabel("Taylor deformation (L - B) / (L + B)")
    plt.legend()
    plt.tight_layout()
    plt.savefig(os.path.join(out, "taylor.png"), dpi=120)
    print("plot: " + os.path.join(out, "taylor.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "viscosity_sweep"))
