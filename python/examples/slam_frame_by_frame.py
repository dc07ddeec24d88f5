"""Run the SLAM frame by frame from arrays and watch what rejection keeps.

    PYTHONPATH=build/python python3 python/examples/slam_frame_by_frame.py DATASET_OR_BAG [full]
"""
import sys

import depot


def main(data, mode="full"):
    seq = depot.Sequence(data)
    slam = depot.Slam(data, mode=mode)
    for i in range(len(seq)):
        f = seq[i]
        r = slam.track(f["rgb"], f["depth"], f["timestamp"])
        kept = r.get("keypoint_kept")
        share = f"{kept.mean():.0%} of keypoints kept" if kept is not None and len(kept) else ""
        print(f"frame {i}: {r['state']} {share}")
    slam.finish()
    stamps, poses = slam.trajectory()
    print(f"{len(stamps)} of {len(seq)} frames posed")


if __name__ == "__main__":
    main(*sys.argv[1:3])
