"""hoilcd.Dataset reads a dataset folder as numpy arrays that agree with one another and with
the files; bad frames and folders are Python exceptions with hoilcd's messages."""
import json
import os

import numpy as np
import pytest

import hoilcd


@pytest.fixture(scope="module")
def ds(tiny_dataset):
    return hoilcd.Dataset(tiny_dataset)


def test_length_and_manifest_match_the_folder(ds, tiny_dataset):
    with open(os.path.join(tiny_dataset, "manifest.json")) as f:
        manifest = json.load(f)
    assert len(ds) == manifest["frame_count"] == 440
    assert ds.manifest == manifest
    assert ds.scene["name"] == "tiny_room"


def test_thermal_is_uint8_height_by_width(ds):
    image = ds.thermal(3)
    assert image.dtype == np.uint8 and image.shape == (96, 128)
    assert image.max() > image.min()


def test_temperature_radiometric_and_exr_agree(ds):
    t = ds.temperature_c(5)
    assert t.dtype == np.float32 and t.shape == (96, 128)
    raw = ds.radiometric(5)
    assert raw.dtype == np.uint16
    np.testing.assert_allclose(t, raw / 100.0 - 273.15, atol=1e-3)
    exr = ds.exr(5)
    assert {"T", "T_true", "Z", "id", "class"} <= set(exr)
    assert all(c.dtype == np.float32 and c.shape == (96, 128) for c in exr.values())
    # The PNG holds the EXR's apparent temperature in centikelvin.
    np.testing.assert_allclose(t, exr["T"], atol=0.006)


def test_thermal_is_the_temperature_over_the_display_window(ds):
    m = ds.manifest
    t = ds.temperature_c(7).astype(np.float64)
    expected = np.clip((t - m["window_min_c"]) / (m["window_max_c"] - m["window_min_c"]) * 255.0, 0, 255)
    assert np.abs(ds.thermal(7) - expected).max() <= 1.01


def test_poses_are_columns_of_poses_csv(ds, tiny_dataset):
    poses = ds.poses
    assert set(poses) >= {"frame", "t", "x", "y", "theta", "cam_x", "cam_yaw", "odo_x", "odo_y", "odo_theta"}
    assert all(len(v) == len(ds) for v in poses.values())
    np.testing.assert_array_equal(poses["frame"], np.arange(len(ds)))
    with open(os.path.join(tiny_dataset, "poses.csv")) as f:
        header = f.readline().strip().split(",")
        row = dict(zip(header, map(float, f.readline().split(","))))
    assert poses["x"][0] == row["x"] and poses["odo_theta"][0] == row["odo_theta"]


def test_persons_are_the_frames_entries_of_persons_json(ds, tiny_dataset):
    with open(os.path.join(tiny_dataset, "persons.json")) as f:
        frames = json.load(f)["frames"]
    entry = next(f for f in frames if f["persons"])
    assert ds.persons(entry["frame"]) == entry["persons"]
    person = ds.persons(entry["frame"])[0]
    assert {"id", "box_px", "visible_fraction", "occlusion_fraction", "keypoints"} <= set(person)


def test_negative_frames_count_from_the_end(ds):
    np.testing.assert_array_equal(ds.thermal(-1), ds.thermal(len(ds) - 1))


def test_a_frame_outside_the_dataset_is_an_index_error(ds):
    with pytest.raises(IndexError, match="frame 440 outside the dataset's 440 frames"):
        ds.thermal(440)
    with pytest.raises(IndexError):
        ds.exr(-441)


def test_a_missing_folder_is_an_input_error_naming_it(tmp_path, hoilcd_exe):
    from conftest import run_cli
    missing = str(tmp_path / "nowhere")
    with pytest.raises(hoilcd.InputError) as error:
        hoilcd.Dataset(missing)
    assert isinstance(error.value, ValueError)
    assert missing in str(error.value)
    code, _, stderr = run_cli(hoilcd_exe, "bench", missing)
    assert code == 1 and stderr.strip() == "error: " + str(error.value)


def _checksum(data):
    """hoilcd's file checksum (ChecksumOf): XXH3-128, canonical (big-endian) hex, from libxxhash."""
    import ctypes

    class Hash128(ctypes.Structure):
        _fields_ = [("low64", ctypes.c_uint64), ("high64", ctypes.c_uint64)]

    xxhash = ctypes.CDLL("libxxhash.so.0")
    xxhash.XXH3_128bits.restype = Hash128
    xxhash.XXH3_128bits.argtypes = [ctypes.c_char_p, ctypes.c_size_t]
    h = xxhash.XXH3_128bits(data, len(data))
    return f"xxh3-128:{h.high64:016x}{h.low64:016x}"


def _with_runs(source, folder, runs):
    """A copy of the dataset `source` in `folder` with runs.json listed in its manifest."""
    import shutil
    shutil.copytree(source, folder)
    text = json.dumps({"runs": runs}, indent=1).encode()
    with open(os.path.join(folder, "runs.json"), "wb") as f:
        f.write(text)
    path = os.path.join(folder, "manifest.json")
    with open(path) as f:
        manifest = json.load(f)
    manifest["files"]["runs.json"] = _checksum(text)
    del manifest["manifest_checksum"]
    manifest["manifest_checksum"] = _checksum(json.dumps(manifest, indent=2, sort_keys=True,
                                                         ensure_ascii=False).encode())
    with open(path, "w") as f:
        json.dump(manifest, f, indent=2, sort_keys=True, ensure_ascii=False)
    return folder


def test_runs_come_from_runs_json_and_number_each_pose(ds, tiny_dataset, tmp_path):
    assert ds.runs == [{"first_frame": 0, "frames": 440, "time_of_day_h": -1, "day": 0, "start_time_s": 0,
                        "seed": 0}]
    assert ds.poses["run"].dtype == np.int32
    np.testing.assert_array_equal(ds.poses["run"], np.zeros(440))
    runs = [{"first_frame": 0, "frames": 300, "time_of_day_h": 9.0, "day": 0, "start_time_s": 0, "seed": 1},
            {"first_frame": 300, "frames": 140, "time_of_day_h": 14.5, "day": 1, "start_time_s": 106200.5,
             "seed": 2}]
    two = hoilcd.Dataset(_with_runs(tiny_dataset, str(tmp_path / "two"), runs))
    assert two.runs == runs
    np.testing.assert_array_equal(two.poses["run"], np.repeat([0, 1], [300, 140]))
    runs[1]["first_frame"] = 301
    with pytest.raises(hoilcd.InputError, match=r"runs.json: /runs/1/first_frame: expected 300"):
        hoilcd.Dataset(_with_runs(tiny_dataset, str(tmp_path / "gap"), runs))
