#!/usr/bin/python3
"""Open3D's RGB-D odometry (Debian python3-open3d) as a system under test.

Frame-to-frame: each frame is registered to the one before it with
compute_rgbd_odometry (hybrid photometric + geometric term, default
options) and the motions are chained into camera-to-world poses. A frame
whose registration fails gets no pose (the chain assumes no motion there),
as a SLAM system reports a lost frame.

usage: open3d_odometry.py DATASET INTRINSICS DEPTH_FACTOR TRAJECTORY
  DATASET       TUM RGB-D folder (associations.txt: t_rgb rgb t_depth depth)
  INTRINSICS    text file "fx fy cx cy"
  DEPTH_FACTOR  depth PNG value per metre (5000 for TUM)
  TRAJECTORY    output, TUM format (timestamp tx ty tz qx qy qz qw)
"""
import os
import sys

import numpy as np
import open3d as o3d


def read_associations(folder):
    path = os.path.join(folder, "associations.txt")
    rows = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            if len(fields) < 4:
                sys.exit(f"{path}:{n}: expected 't_rgb rgb t_depth depth'")
            rows.append((fields[0], fields[1], fields[3]))
    return rows


def quaternion_xyzw(r):
    """Unit quaternion (x, y, z, w) of a rotation matrix (Shepperd's method)."""
    t = np.trace(r)
    if t > 0:
        s = 2.0 * np.sqrt(t + 1.0)
        q = [(r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s, 0.25 * s]
    else:
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k])
        q = [0.0, 0.0, 0.0, (r[k, j] - r[j, k]) / s]
        q[i] = 0.25 * s
        q[j] = (r[j, i] + r[i, j]) / s
        q[k] = (r[k, i] + r[i, k]) / s
    q = np.array(q)
    return q / np.linalg.norm(q)


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    folder, intrinsics_path, depth_factor, out_path = sys.argv[1:]
    fx, fy, cx, cy = (float(v) for v in open(intrinsics_path).read().split())
    frames = read_associations(folder)
    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)

    def rgbd(i):
        color = o3d.io.read_image(os.path.join(folder, frames[i][1]))
        depth = o3d.io.read_image(os.path.join(folder, frames[i][2]))
        return o3d.geometry.RGBDImage.create_from_color_and_depth(
            color, depth, depth_scale=float(depth_factor), depth_trunc=4.5,
            convert_rgb_to_intensity=True)

    first = rgbd(0)
    width, height = np.asarray(first.depth).shape[1], np.asarray(first.depth).shape[0]
    camera = o3d.camera.PinholeCameraIntrinsic(width, height, fx, fy, cx, cy)
    option = o3d.pipelines.odometry.OdometryOption()
    jacobian = o3d.pipelines.odometry.RGBDOdometryJacobianFromHybridTerm()
    pose = np.eye(4)
    lines = []

    def keep(i):
        q = quaternion_xyzw(pose[:3, :3])
        t = pose[:3, 3]
        lines.append(f"{frames[i][0]} {t[0]:.9f} {t[1]:.9f} {t[2]:.9f} "
                     f"{q[0]:.9f} {q[1]:.9f} {q[2]:.9f} {q[3]:.9f}\n")

    keep(0)
    previous = first
    for i in range(1, len(frames)):
        current = rgbd(i)
        ok, motion, _ = o3d.pipelines.odometry.compute_rgbd_odometry(
            previous, current, camera, np.eye(4), jacobian, option)
        if ok:
            # motion maps the previous camera's points into the current one's.
            pose = pose @ np.linalg.inv(motion)
            keep(i)
        previous = current
        print(f"frame {i + 1}/{len(frames)} {'ok' if ok else 'lost'}", flush=True)
    with open(out_path, "w") as f:
        f.write("# timestamp tx ty tz qx qy qz qw (Open3D frame-to-frame RGB-D odometry)\n")
        f.writelines(lines)


if __name__ == "__main__":
    main()
