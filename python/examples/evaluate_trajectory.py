"""Score an external system's trajectory against a dataset's (or bag's) truth,
and plot the errors where matplotlib is installed.

    PYTHONPATH=build/python python3 python/examples/evaluate_trajectory.py DATASET_OR_BAG TRAJ.txt [plot.png]
"""
import os
import sys

import depot


def main(reference, estimate, plot=None):
    if os.path.isdir(reference):
        reference = os.path.join(reference, "groundtruth.txt")
    r = depot.ate(reference, estimate)
    print(f"ATE rmse {r['rmse'] * 1000:.1f} mm, median {r['median'] * 1000:.1f} mm "
          f"over {r['matched']} poses")
    if plot:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("matplotlib is not installed: no plot")
            return
        plt.plot(r["errors"] * 1000)
        plt.xlabel("matched pose")
        plt.ylabel("error after alignment (mm)")
        plt.savefig(plot)
        print(f"wrote {plot}")


if __name__ == "__main__":
    main(*sys.argv[1:4])
