#!/usr/bin/env python3
"""report.html in a real browser: `hoilcd run` on the tiny room, then headless Chromium (Debian's
chromium, which scripts/setup installs) loads the page. It must log nothing to the console, its
gallery must hold exactly the queries report.json lists (no two within min_gap_frames, and at least
min(n, per_group) hits and misses of each method from queries.csv, or each of the others within the
gap of a sampled query), a click on a results header must sort the column both
ways, the gallery's filters must work, every image must decode, and a screenshot must be taken.
When Chromium is missing or cannot run, the test fails: it never skips.

usage: report_html_test.py HOILCD SOURCE_DIR
"""
import csv
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Loads report.html in a frame of its own folder's parent, then reads and drives its DOM.
PROBE = """<!DOCTYPE html><html><body><pre id="verdict">pending</pre>
<iframe id="page" src="report/report.html" width="1280" height="900"></iframe>
<script>
window.addEventListener('load', function () {
  var out = {};
  try {
    var d = document.getElementById('page').contentDocument;
    out.entries = Array.prototype.map.call(d.querySelectorAll('#gallery .entry'),
                                           function (e) { return +e.getAttribute('data-query'); });
    var table = d.querySelector('table.sortable');
    var column = function () {
      return Array.prototype.map.call(table.tBodies[0].rows, function (r) { return r.cells[1].getAttribute('data-sort'); });
    };
    out.before = column();
    table.querySelectorAll('th')[1].click();
    out.ascending = column();
    table.querySelectorAll('th')[1].click();
    out.descending = column();
    var images = d.querySelectorAll('img');
    out.images = images.length;
    out.broken = Array.prototype.filter.call(images, function (i) { return !(i.naturalWidth > 0); }).length;
    out.frames = d.querySelectorAll('defs image').length;
    out.svg_trajectories = d.querySelectorAll('svg.trajectories polyline').length;
    var outcome = d.getElementById('gallery-outcome'), method = d.getElementById('gallery-method');
    var shown = function () { return d.querySelectorAll('#gallery .entry:not(.hidden)').length; };
    out.shown_all = shown();
    method.value = 'slcd'; outcome.value = 'hit';
    outcome.dispatchEvent(new Event('change'));
    out.shown_slcd_hit = shown();
    out.expected_slcd_hit = Array.prototype.filter.call(d.querySelectorAll('#gallery .entry'), function (e) {
      return e.getAttribute('data-outcomes').split('|').indexOf('slcd:hit') >= 0; }).length;
    out.visible_tiles_per_entry = d.querySelectorAll('#gallery .entry:not(.hidden) .tile.pair:not(.hidden)').length;
    out.shown_text = d.getElementById('gallery-shown').textContent;
  } catch (e) {
    out.error = String(e);
  }
  document.getElementById('verdict').textContent = JSON.stringify(out);
});
</script></body></html>
"""


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def chromium(args, profile, timeout=180):
    exe = shutil.which("chromium")
    if exe is None:
        fail("chromium is not installed (scripts/setup installs Debian's chromium and chromium-driver)")
    command = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--user-data-dir=" + profile,
               "--enable-logging=stderr", "--v=0"] + args
    done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    if done.returncode != 0:
        fail("chromium exited %d: %s\n%s" % (done.returncode, " ".join(command), done.stderr[-3000:]))
    return done


def console_lines(stderr):
    return [line for line in stderr.splitlines() if ":CONSOLE" in line]


def main():
    hoilcd, source = sys.argv[1], sys.argv[2]
    temp = tempfile.mkdtemp(prefix="hoilcd_%d_report_html_" % os.getpid())
    try:
        report = os.path.join(temp, "report")
        run = subprocess.run([hoilcd, "run", os.path.join(source, "tests/data/tiny_room.json"), "--cache",
                              os.path.join(temp, "cache"), "-o", report], capture_output=True, text=True)
        if run.returncode != 0:
            fail("hoilcd run failed:\n" + run.stdout[-2000:] + run.stderr[-2000:])
        page = os.path.join(report, "report.html")
        if not os.path.isfile(page):
            fail("hoilcd run wrote no report.html")
        with open(os.path.join(report, "report.json")) as f:
            gallery = json.load(f)["gallery"]
        expected = gallery["query_frames"]
        if not expected:
            fail("report.json lists an empty gallery")
        check_sampling(os.path.join(report, "queries.csv"), expected, gallery["per_group"], gallery["min_gap_frames"])

        profile = os.path.join(temp, "profile")
        loaded = chromium(["--virtual-time-budget=10000", "--dump-dom", "file://" + page], profile)
        if console_lines(loaded.stderr):
            fail("console messages while loading report.html:\n" + "\n".join(console_lines(loaded.stderr)))
        if loaded.stdout.count('<div class="entry"') != len(expected):
            fail("the loaded DOM holds %d gallery entries, report.json lists %d"
                 % (loaded.stdout.count('<div class="entry"'), len(expected)))

        probe = os.path.join(temp, "probe.html")
        with open(probe, "w") as f:
            f.write(PROBE)
        probed = chromium(["--allow-file-access-from-files", "--virtual-time-budget=10000", "--dump-dom",
                           "file://" + probe], profile)
        if console_lines(probed.stderr):
            fail("console messages while driving report.html:\n" + "\n".join(console_lines(probed.stderr)))
        match = re.search(r'<pre id="verdict">(.*?)</pre>', probed.stdout, re.S)
        if match is None:
            fail("the probe page wrote no verdict")
        verdict = json.loads(html.unescape(match.group(1)))
        check_verdict(verdict, expected)

        shot = os.path.join(temp, "report.png")
        chromium(["--window-size=1280,2000", "--hide-scrollbars", "--virtual-time-budget=10000",
                  "--screenshot=" + shot, "file://" + page], profile)
        with open(shot, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                fail("the screenshot is not a PNG")
        if os.path.getsize(shot) < 20000:
            fail("the screenshot is nearly empty (%d bytes)" % os.path.getsize(shot))
        print("ok: %d gallery entries, %d frames, %d figures, report.html %d bytes, screenshot %d bytes"
              % (len(expected), verdict["frames"], verdict["images"], os.path.getsize(page), os.path.getsize(shot)))
    finally:
        shutil.rmtree(temp, ignore_errors=True)


def check_sampling(queries_csv, sampled, per_group, min_gap_frames):
    """No two sampled queries within the gap; every method's hits and misses: at least
    min(their count, per_group) of them are sampled, or each of the others is within the gap of a
    sampled query."""
    for a, b in zip(sampled, sampled[1:]):
        if b - a < min_gap_frames:
            fail("sampled queries %d and %d are closer than %d frames" % (a, b, min_gap_frames))
    near_sample = lambda frame: any(abs(frame - s) < min_gap_frames for s in sampled)
    groups = {}
    with open(queries_csv) as f:
        for row in csv.DictReader(f):
            if row["scored"] != "1":
                continue
            key = (row["method"], "hit" if row["top1_is_true_match"] == "1" else "miss")
            groups.setdefault(key, []).append(int(row["frame"]))
    if not groups:
        fail("queries.csv holds no scored query")
    for key, frames in groups.items():
        in_sample = sum(frame in sampled for frame in frames)
        crowded_out = all(near_sample(frame) for frame in frames if frame not in sampled)
        if in_sample < min(len(frames), per_group) and not crowded_out:
            fail("%s %s: %d of %d queries sampled, fewer than %d" % (key + (in_sample, len(frames), per_group)))


def check_verdict(v, expected):
    if "error" in v:
        fail("the probe failed: " + v["error"])
    if v["entries"] != expected:
        fail("gallery entries %s, report.json lists %s" % (v["entries"], expected))
    keys = lambda column: [float(k) for k in column]
    if keys(v["ascending"]) != sorted(keys(v["before"])) or keys(v["descending"]) != sorted(keys(v["before"]), reverse=True):
        fail("a click on the MRR header does not sort: %s -> %s -> %s" % (v["before"], v["ascending"], v["descending"]))
    if v["images"] == 0 or v["broken"] != 0:
        fail("%d of %d figures do not decode" % (v["broken"], v["images"]))
    if v["frames"] == 0 or v["svg_trajectories"] < 2:
        fail("no frames (%d) or SLAM trajectories (%d) in the page" % (v["frames"], v["svg_trajectories"]))
    if v["shown_all"] != len(expected) or v["shown_slcd_hit"] != v["expected_slcd_hit"]:
        fail("filters: %d shown of %d at first, %d for slcd hits where %d are"
             % (v["shown_all"], len(expected), v["shown_slcd_hit"], v["expected_slcd_hit"]))
    if v["visible_tiles_per_entry"] != v["shown_slcd_hit"]:
        fail("filtered by slcd, %d method tiles are visible in %d entries" % (v["visible_tiles_per_entry"], v["shown_slcd_hit"]))


if __name__ == "__main__":
    main()
