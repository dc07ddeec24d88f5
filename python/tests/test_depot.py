# `import depot`: render to arrays, SLAM frame by frame, ATE, bags, and bad
# input as Python exceptions carrying the one-line messages.
import json
import os
import subprocess

import numpy as np
import pytest

import depot


def test_frames_come_as_arrays_with_their_truth(walking):
    seq = depot.Sequence(walking)
    assert len(seq) == 30
    f = seq[0]
    assert f["rgb"].dtype == np.uint8 and f["rgb"].shape == (120, 160, 3)
    assert f["depth"].dtype == np.float32 and f["depth"].shape == (120, 160)
    assert f["labels"].dtype == np.uint16 and f["labels"].shape == (120, 160)
    assert f["pose"].shape == (4, 4)
    np.testing.assert_allclose(f["pose"][:3, :3] @ f["pose"][:3, :3].T, np.eye(3), atol=1e-9)
    # Depth in metres, where the sensor sees (the hall is a few metres deep).
    valid = f["depth"][f["depth"] > 0]
    assert 0.3 < np.median(valid) < 10.0
    # A labelled person has a box around its pixels.
    people = [b for b in seq[15]["boxes"] if b["class"] == "person"]
    assert people
    x1, y1, x2, y2 = people[0]["box"]
    assert (seq[15]["labels"][y1:y2, x1:x2] == people[0]["id"]).sum() == people[0]["visible_pixels"]
    assert seq[-1]["timestamp"] == seq.timestamps[-1]


def test_full_frame_by_frame_gives_the_ate_of_depot_slam_run(walking, scratch, depot_program):
    seq = depot.Sequence(walking)
    slam = depot.Slam(walking, mode="full", detector="darknet")
    states = []
    for i in range(len(seq)):
        f = seq[i]
        r = slam.track(f["rgb"], f["depth"], f["timestamp"])
        states.append(r["state"])
        assert r["keypoint_xy"].shape[0] == r["keypoint_kept"].shape[0]
    slam.finish()
    stamps, poses = slam.trajectory()
    assert len(stamps) >= 28 and poses.shape == (len(stamps), 4, 4)
    ours = depot.ate(os.path.join(walking, "groundtruth.txt"), (stamps, poses))

    out = os.path.join(scratch, "cli_full.txt")
    subprocess.run([depot_program, "slam", "run", walking, "--mode", "full", "--detector",
                    "darknet", "--mapping", "sync", "-q", "-o", out], check=True)
    theirs = depot.ate(os.path.join(walking, "groundtruth.txt"), out)
    assert ours["matched"] == theirs["matched"]
    # The CLI's file holds nine digits: the same run to that precision.
    assert ours["rmse"] == pytest.approx(theirs["rmse"], abs=1e-8)
    assert ours["rmse"] < 0.05
    rpe = depot.rpe(os.path.join(walking, "groundtruth.txt"), (stamps, poses), delta=5, unit="f")
    report = os.path.join(scratch, "rpe.json")
    subprocess.run([depot_program, "eval", "rpe", os.path.join(walking, "groundtruth.txt"), out,
                    "--delta", "5", "--delta-unit", "f", "--json", report], check=True,
                   stdout=subprocess.DEVNULL)
    with open(report) as f:
        cli = json.load(f)
    assert rpe["pairs"] == cli["pairs"] == 25
    assert rpe["translation_rmse"] == pytest.approx(cli["translation"]["statistics"]["rmse"], abs=1e-8)


def test_slam_run_scores_rejection_on_a_simulated_dataset(walking):
    run = depot.slam_run(walking, mode="full", detector="darknet")
    assert run["tracked"] >= 28 and len(run["states"]) == 30
    # Scored against the labels as `depot slam run` scores it (0.645 / 0.876 when written).
    assert run["rejection_recall"] > 0.7
    assert run["rejection_precision"] > 0.5
    assert run["rejection_precision_boundary_static"] < run["rejection_precision"]


def test_slam_run_and_bags(walking, scratch):
    bag = os.path.join(scratch, "walking.mcap")
    info = depot.export_mcap(walking, bag)
    assert info["frames"] == 30 and "/camera/color/image_raw" in info["topics"]
    on_bag = depot.slam_run(bag, mode="orb")
    on_folder = depot.slam_run(walking, mode="orb")
    np.testing.assert_array_equal(on_bag["poses"], on_folder["poses"])
    # The bag's own truth is the folder's.
    estimate = (on_bag["timestamps"], on_bag["poses"])
    from_bag = depot.ate(bag, estimate)
    assert from_bag["matched"] == on_bag["tracked"]
    assert from_bag["rmse"] == depot.ate(os.path.join(walking, "groundtruth.txt"), estimate)["rmse"]
    assert len(depot.Sequence(bag)) == 30


def test_bad_input_is_one_clear_exception(walking, scratch):
    slam = depot.Slam(walking)
    f = depot.Sequence(walking)[0]
    with pytest.raises(depot.Error, match=r"rgb: must be an H x W x 3 uint8 array, got float64"):
        slam.track(f["rgb"].astype(np.float64), f["depth"], 0.0)
    with pytest.raises(depot.Error, match=r"depth: must be an H x W float32 array of metres, got uint16"):
        slam.track(f["rgb"], (f["depth"] * 1000).astype(np.uint16), 0.0)
    with pytest.raises(depot.Error, match=r"depth: is \(60, 80\) but rgb is \(120, 160\)"):
        slam.track(f["rgb"], f["depth"][::2, ::2].copy(), 0.0)
    with pytest.raises(depot.Error, match=r"no_such_scenario: scenario not found"):
        depot.render("no_such_scenario", os.path.join(scratch, "x"))
    with pytest.raises(depot.Error, match=r"nothing.mcap: no such MCAP file"):
        depot.Sequence(os.path.join(scratch, "nothing.mcap"))
    with pytest.raises(depot.Error, match=r"fastest"):
        depot.Slam(walking, mode="fastest")
    with pytest.raises(depot.Error, match=r"estimate: must be timestamps \(N,\) and poses \(N, 4, 4\)"):
        depot.ate(os.path.join(walking, "groundtruth.txt"), (np.zeros(3), np.zeros((3, 3, 3))))
    with pytest.raises(IndexError):
        depot.Sequence(walking)[30]


def test_a_scenario_stepped_in_memory_is_the_rendered_dataset(walking):
    sim = depot.Simulation("depot_walking_xyz", frames=30, seed=1, width=160)
    assert sim.frames == 30 and sim.camera["width"] == 160
    seq = depot.Sequence(walking)
    for i in range(3):
        f = sim.step()
        g = seq[i]
        assert f["timestamp"] == g["timestamp"]
        np.testing.assert_array_equal(f["rgb"], g["rgb"])  # colour is stored losslessly
        np.testing.assert_array_equal(f["labels"], g["labels"])
        np.testing.assert_allclose(f["pose"], g["pose"], atol=1e-6)
        # The dataset stores depth in steps of 1/5000 m.
        assert np.abs(f["depth"] - g["depth"]).max() <= 0.5 / 5000 + 1e-6
        assert any(o["moving"] for o in f["objects"])
    for _ in range(27):
        assert sim.step() is not None
    assert sim.step() is None


def test_a_sweep_returns_its_run_records(scratch):
    records = depot.sweep(["depot_static"], os.path.join(scratch, "sweep"), modes=["orb"],
                          seeds=1, frames=12, width=160, vary={"light": ["1", "0.5"]})
    assert len(records) == 2
    assert {r["mode"] for r in records} == {"orb"}
    assert all(r["ok"] and r["tracked"] == 12 for r in records)
    with pytest.raises(depot.Error, match=r"--vary"):
        depot.sweep(["depot_static"], os.path.join(scratch, "sweep2"), vary={"no_such_key": ["1"]})
