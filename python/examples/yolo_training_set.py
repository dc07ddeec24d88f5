"""Generate a YOLO training set over a range of dynamic load.

For each load, render a short walking scenario and write every frame's RGB
image with a YOLO label file (class index, centre and size normalised) from
the simulator's exact boxes.

    PYTHONPATH=build/python python3 python/examples/yolo_training_set.py OUT
"""
import os
import sys

import numpy as np

import depot

try:
    import cv2  # python3-opencv, if installed, writes the images
except ImportError:
    cv2 = None


def main(out, loads=(0.5, 1.0, 2.0), frames=30):
    classes = {}
    for load in loads:
        data = os.path.join(out, f"load_{load}")
        depot.render("depot_walking_xyz", data, frames=frames, seed=1, load=load)
        seq = depot.Sequence(data)
        for i in range(len(seq)):
            f = seq[i]
            h, w = f["depth"].shape
            stem = os.path.join(out, "images", f"load{load}_{i:05d}")
            os.makedirs(os.path.dirname(stem), exist_ok=True)
            if cv2 is not None:
                cv2.imwrite(stem + ".png", f["rgb"][:, :, ::-1])
            else:
                np.save(stem + ".npy", f["rgb"])
            with open(stem + ".txt", "w") as labels:
                for b in f["boxes"]:
                    k = classes.setdefault(b["class"], len(classes))
                    x1, y1, x2, y2 = b["box"]
                    labels.write(f"{k} {(x1 + x2) / 2 / w:.6f} {(y1 + y2) / 2 / h:.6f} "
                                 f"{(x2 - x1) / w:.6f} {(y2 - y1) / h:.6f}\n")
    with open(os.path.join(out, "classes.txt"), "w") as names:
        names.writelines(f"{name}\n" for name in sorted(classes, key=classes.get))
    print(f"{out}: {len(loads) * frames} images, classes {sorted(classes, key=classes.get)}")


if __name__ == "__main__":
    main(sys.argv[1])
