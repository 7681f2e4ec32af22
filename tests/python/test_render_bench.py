"""hoilcd.render and hoilcd.bench do what `hoilcd render` and `hoilcd bench` do: the same bytes,
the same metrics, the same error messages."""
import json
import os

import pytest

import hoilcd
from conftest import run_cli


def test_render_writes_the_same_dataset_as_the_cli(tmp_path, hoilcd_exe, tiny_scene):
    py = hoilcd.render(tiny_scene, str(tmp_path / "py"), frames=4, seed=7,
                       set={"crowd.people_per_table": 2}, threads=2)
    assert isinstance(py, hoilcd.Dataset) and len(py) == 4
    code, _, stderr = run_cli(hoilcd_exe, "render", tiny_scene, "-o", str(tmp_path / "cli"), "--frames", "4",
                              "--seed", "7", "--set", "crowd.people_per_table=2", "--threads", "1")
    assert code == 0, stderr
    assert py.manifest["files"] == hoilcd.Dataset(str(tmp_path / "cli")).manifest["files"]
    assert py.manifest["seed"] == 7


def test_a_bad_override_is_an_input_error_with_the_cli_message(tmp_path, hoilcd_exe, tiny_scene):
    with pytest.raises(hoilcd.InputError) as error:
        hoilcd.render(tiny_scene, str(tmp_path / "py"), frames=1, set={"crowd.people_per_tabel": 2})
    assert "people_per_tabel" in str(error.value)
    code, _, stderr = run_cli(hoilcd_exe, "render", tiny_scene, "-o", str(tmp_path / "cli"), "--frames", "1",
                              "--set", "crowd.people_per_tabel=2")
    assert code == 1 and stderr.strip() == "error: " + str(error.value)


def test_bench_gives_the_cli_reports_metrics(tmp_path, hoilcd_exe, tiny_dataset):
    methods = ["slcd", "dlcd", "fusion"]
    py = hoilcd.bench(hoilcd.Dataset(tiny_dataset), methods=methods, threads=2)
    assert set(py["methods"]) == set(methods)
    code, _, stderr = run_cli(hoilcd_exe, "bench", tiny_dataset, "--methods", ",".join(methods),
                              "-o", str(tmp_path / "report"), "--threads", "2")
    assert code == 0, stderr
    with open(tmp_path / "report" / "report.json") as f:
        cli = json.load(f)
    for name in methods:
        assert py["methods"][name]["mrr"] == cli["methods"][name]["mrr"]
        assert py["methods"][name]["recall_at_1"] == cli["methods"][name]["recall_at_1"]
        assert py["methods"][name]["queries_scored"] > 0
        assert py["methods"][name]["intervals"] == cli["methods"][name]["intervals"]
    assert py["strata"] == cli["strata"]
    assert py["comparisons"] == cli["comparisons"]
    assert py["bootstrap"] == cli["bootstrap"]


def test_bench_with_an_output_writes_the_report_folder(tmp_path, tiny_dataset):
    report = hoilcd.bench(hoilcd.Dataset(tiny_dataset), methods=["slcd"], output=str(tmp_path / "r"))
    assert os.path.isfile(tmp_path / "r" / "report.md")
    assert 0 <= report["methods"]["slcd"]["mrr"] <= 1


def test_an_unknown_method_is_an_input_error(tiny_dataset):
    with pytest.raises(hoilcd.InputError, match="--methods"):
        hoilcd.bench(hoilcd.Dataset(tiny_dataset), methods=["nope"])


def test_a_negative_seed_is_an_input_error(tmp_path, tiny_scene):
    with pytest.raises(hoilcd.InputError, match="seed: a non-negative integer; got -1"):
        hoilcd.render(tiny_scene, str(tmp_path / "x"), frames=1, seed=-1)


def test_data_dir_holds_the_shipped_scenes():
    assert os.path.isfile(os.path.join(hoilcd.data_dir(), "scenes", "paper_room.json"))
