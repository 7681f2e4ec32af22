"""hoilcd.evaluate applies the benchmark's protocol, labels and metrics to a numpy method's score
matrix and agrees exactly with `hoilcd evaluate --scores` on the same scores; its `output` is a
report folder as `hoilcd evaluate -o`'s; the numpy example (examples/python/numpy_method.py) runs
end to end."""
import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import hoilcd
from conftest import run_cli

EXAMPLES = os.path.join(os.environ["HOILCD_TEST_SOURCE_DIR"], "examples", "python")
sys.path.insert(0, EXAMPLES)
import numpy_method  # noqa: E402


@pytest.fixture(scope="module")
def ds(tiny_dataset):
    return hoilcd.Dataset(tiny_dataset)


@pytest.fixture(scope="module")
def scores(ds):
    return numpy_method.score_matrix(ds)


def without_description(metrics):
    return {k: v for k, v in metrics.items() if k != "description"}


def test_a_numpy_method_gets_the_same_metrics_as_its_npy_through_the_cli(tmp_path, hoilcd_exe, ds, scores):
    py = hoilcd.evaluate(ds, scores, name="numpy_thumb", output=str(tmp_path / "py"))
    assert py["queries_scored"] > 0 and 0 < py["mrr"] <= 1
    np.save(tmp_path / "numpy_thumb.npy", scores)
    code, stdout, stderr = run_cli(hoilcd_exe, "evaluate", ds.dir, "--scores", str(tmp_path / "numpy_thumb.npy"),
                                   "-o", str(tmp_path / "report"))
    assert code == 0, stderr
    with open(tmp_path / "report" / "report.json") as f:
        cli_report = json.load(f)
    cli = cli_report["methods"]["numpy_thumb"]
    assert py["mrr"] == cli["mrr"]
    assert without_description(py) == without_description(cli)
    # The protocol's defaults are the command line's: both read them from ProtocolOptions.
    with open(tmp_path / "py" / "report.json") as f:
        assert json.load(f)["protocol"] == cli_report["protocol"]


def test_the_same_scores_as_csv_give_the_same_mrr(tmp_path, hoilcd_exe, ds, scores):
    with open(tmp_path / "mine.csv", "w") as f:
        f.write("query,reference,score\n")
        for q in range(len(ds)):
            for r in range(len(ds)):
                f.write(f"{q},{r},{scores[q, r]!r}\n")
    code, _, stderr = run_cli(hoilcd_exe, "evaluate", ds.dir, "--scores", str(tmp_path / "mine.csv"),
                              "--name", "mine", "-o", str(tmp_path / "report"))
    assert code == 0, stderr
    with open(tmp_path / "report" / "report.json") as f:
        assert json.load(f)["methods"]["mine"]["mrr"] == hoilcd.evaluate(ds, scores, name="mine")["mrr"]


def test_protocol_and_ground_truth_are_those_of_the_cli(tmp_path, hoilcd_exe, ds, scores):
    py = hoilcd.evaluate(ds.dir, scores.astype(np.float32), name="m", protocol="revisit", ground_truth="true",
                         output=str(tmp_path / "py"))
    np.save(tmp_path / "m.npy", scores.astype(np.float32))
    code, _, stderr = run_cli(hoilcd_exe, "evaluate", ds.dir, "--scores", str(tmp_path / "m.npy"),
                              "--protocol", "revisit", "--ground-truth", "true", "-o", str(tmp_path / "cli"))
    assert code == 0, stderr
    with open(tmp_path / "cli" / "report.json") as f:
        cli = json.load(f)
    with open(tmp_path / "py" / "report.json") as f:
        written = json.load(f)
    assert py["mrr"] == cli["methods"]["m"]["mrr"] == written["methods"]["m"]["mrr"]
    assert written["protocol"] == cli["protocol"]
    # The same report folder: only the method's description (where its scores came from) differs.
    assert sorted(os.listdir(tmp_path / "py")) == sorted(os.listdir(tmp_path / "cli"))
    with open(tmp_path / "py" / "queries.csv") as a, open(tmp_path / "cli" / "queries.csv") as b:
        assert a.read() == b.read()


def test_output_is_a_report_folder_and_a_folder_of_the_users_is_refused(tmp_path, ds, scores):
    hoilcd.evaluate(ds, scores, name="mine", output=str(tmp_path / "report"))
    assert {"report.json", "queries.csv", "report.md", "pr_curves.png"} <= set(os.listdir(tmp_path / "report"))
    with open(tmp_path / "report" / "queries.csv") as f:
        rows = f.read().splitlines()
    assert rows[0].startswith("method,frame,") and rows[1].startswith("mine,") and len(rows) > 10
    hoilcd.evaluate(ds, scores, name="again", output=str(tmp_path / "report"))  # its own earlier folder
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("my own notes")
    with pytest.raises(hoilcd.InputError, match=r"mine: exists, is not empty \(it holds notes.txt\) and holds no "
                                                r"earlier hoilcd report \(report.json\)"):
        hoilcd.evaluate(ds, scores, output=str(tmp_path / "mine"))
    assert os.listdir(tmp_path / "mine") == ["notes.txt"]


def test_unscored_pairs_are_nan(ds, scores):
    partial = scores.copy()
    partial[:, 1::2] = np.nan
    metrics = hoilcd.evaluate(ds, partial, name="half")
    assert not math.isnan(metrics["mrr"]) and metrics["mrr"] != hoilcd.evaluate(ds, scores)["mrr"]


def test_queries_with_no_scored_pair_are_warned_about(ds, scores):
    partial = scores.copy()
    partial[1::2, :] = np.nan  # every other query row
    with pytest.warns(UserWarning, match=r"^scores: \d+ of the \d+ queries with a true match have no scored pair"):
        hoilcd.evaluate(ds, partial, name="half")


def test_an_object_array_of_none_or_all_nan_is_refused_not_scored_as_a_random_order(ds):
    for empty in (np.full((len(ds), len(ds)), None, dtype=object), np.full((len(ds), len(ds)), np.nan)):
        with pytest.raises(hoilcd.InputError, match=r"^scores: scores none of the \d+ \(query, database frame\) pairs"):
            hoilcd.evaluate(ds, empty)


def test_a_matrix_of_the_wrong_shape_is_an_input_error(ds, scores):
    with pytest.raises(hoilcd.InputError, match=r"scores: a frames x frames matrix \(440 x 440\); got shape \(440, 439\)"):
        hoilcd.evaluate(ds, scores[:, :-1])
    with pytest.raises(hoilcd.InputError, match=r"scores: a 439 x 439 matrix: expected 440 x 440"):
        hoilcd.evaluate(ds, scores[:-1, :-1])
    with pytest.raises(hoilcd.InputError, match=r"got shape \(440\)"):
        hoilcd.evaluate(ds, scores[0])


def test_infinite_scores_and_a_bad_protocol_are_input_errors(ds, scores):
    bad = scores.copy()
    bad[300, 0] = np.inf
    with pytest.raises(hoilcd.InputError, match="is infinite: expected a finite score, or NaN for unscored"):
        hoilcd.evaluate(ds, bad)
    with pytest.raises(hoilcd.InputError, match="^protocol: "):
        hoilcd.evaluate(ds, scores, protocol="laps2")
    with pytest.raises(hoilcd.InputError, match="^name: a method name"):
        hoilcd.evaluate(ds, scores, name="")


def test_methods_lists_the_built_ins():
    names = [m["name"] for m in hoilcd.methods()]
    assert names[:3] == ["slcd", "dlcd", "fusion"]
    assert all(m["from_paper"] for m in hoilcd.methods()[:3])


def test_the_numpy_example_runs_end_to_end(tmp_path, ds):
    env = dict(os.environ)
    done = subprocess.run([sys.executable, os.path.join(EXAMPLES, "numpy_method.py"), ds.dir,
                           "-o", str(tmp_path / "report")], capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr
    assert re.match(rf"numpy_thumb on {re.escape(ds.dir)}: MRR [01]\.\d{{3}}, R@1 ", done.stdout), done.stdout
    with open(tmp_path / "report" / "report.json") as f:
        assert "numpy_thumb" in json.load(f)["methods"]
