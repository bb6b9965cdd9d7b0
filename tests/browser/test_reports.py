"""Every result command's `--report DIR` page, rendered in headless Chromium.

For each report: Chromium loads report.html from the file (a fresh profile, no network
features), dumps the DOM and logs to stderr; the page must log no console message and no failed
load, every expected figure must be an inline SVG with drawn content and a non-zero size, every
number cell (data-src/data-json/data-value) must equal the value at its path in the command's
--json output (the exact value, and the shown text to its last digit), and a screenshot is
taken (a PNG of the window size, not blank). Every result page (diagnose, diagnose --iterate,
compare, sweep, paper with table4, table5 and the headline, calibrate, campaign, sea and
schemes analyse) must open with its verdict: the first block after the title and the command
line is the verdict section, each of its numbers (data-json) and counts (data-json-len, an
array's length) equals the --json output, and the block right after it is the figure that
shows the verdict (KEY_FIGURE), before any table.

Usage: python3 tests/browser/test_reports.py RINS_BINARY
"""

import json
import math
import os
import re
import struct
import subprocess
import sys
import tempfile
from html.parser import HTMLParser

CHROMIUM = "/usr/bin/chromium"
FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--hide-scrollbars",
]


def run(cmd, **kw):
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr[-3000:]}")
    return p.stdout


class Page(HTMLParser):
    """Figures (with their SVG size and element count) and number cells of a dumped DOM."""

    def __init__(self):
        super().__init__()
        self.figures = {}
        self.cells = []
        self.stack_fig = None
        self.cell = None
        self.forbidden = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag in ("script", "link", "img", "iframe") or (tag != "svg" and "src" in a):
            self.forbidden.append(tag)
        if tag == "figure" and "data-figure" in a:
            self.stack_fig = a["data-figure"]
            self.figures[self.stack_fig] = {"svg": None, "elements": 0}
        elif self.stack_fig and tag == "svg":
            self.figures[self.stack_fig]["svg"] = (a.get("width"), a.get("height"))
        elif self.stack_fig and tag in ("path", "polyline", "line", "circle", "rect", "polygon", "text"):
            self.figures[self.stack_fig]["elements"] += 1
        if tag in ("td", "span") and "data-json" in a:
            self.cell = {"src": a["data-src"], "path": a["data-json"], "value": a["data-value"],
                         "text": "", "tag": tag}
        elif tag in ("td", "span") and "data-json-len" in a:
            self.cell = {"src": a["data-src"], "len": a["data-json-len"], "text": "", "tag": tag}

    def handle_endtag(self, tag):
        if tag == "figure":
            self.stack_fig = None
        if self.cell is not None and tag == self.cell["tag"]:
            self.cells.append(self.cell)
            self.cell = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell["text"] += data


def lookup(doc, path):
    for k in path.split("."):
        doc = doc[int(k)] if isinstance(doc, list) else doc[k]
    return doc


def last_digit(text):
    """Half a unit of the last shown digit of a number's text."""
    m = re.fullmatch(r"-?\d+(?:\.(\d+))?(?:e(-?\d+))?", text)
    assert m, f"not a number: {text!r}"
    decimals = len(m.group(1) or "")
    exp = int(m.group(2) or 0)
    return 0.5 * 10.0 ** (exp - decimals)


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", path
    return struct.unpack(">II", head[16:24])


# The pages that must open with a verdict that agrees with the JSON, and the figure that must
# come directly after it.
KEY_FIGURE = {
    "paper": "fig3_position_error", "table4": "fig3_position_error",
    "table5": "fig3_position_error", "diagnose": "bias_by_position",
    "compare": "bias_by_position", "iterate": "iteration_history", "sweep": "sweep_lon_nm",
    "calibrate": "calibration_beta", "campaign": "fig8_dbeta_vs_temperature",
    "sea": "sea_end_error", "schemes": "schemes_classes",
}
# The title, the command line, then the verdict: the first block of the page's content.
VERDICT_FIRST = re.compile(
    r'<body[^>]*>\s*<h1>[^<]*</h1>\s*<p class="meta">.*?</p>\s*'
    r'(<section class="verdict" id="verdict">.*?</section>)', re.S)


def check_cells(name, cells, sources):
    """Every number cell equals its JSON value (and shows it to its last digit); every count
    equals its array's length."""
    for c in cells:
        if "len" in c:
            want = len(lookup(sources[c["src"]], c["len"]))
            assert int(c["text"].strip()) == want, (
                f"{name}: {c['src']}:{c['len']} counts {c['text']!r}, json has {want}")
            continue
        want = lookup(sources[c["src"]], c["path"])
        got = float(c["value"])
        assert got == want, f"{name}: {c['src']}:{c['path']} page {got!r} vs json {want!r}"
        shown = c["text"].strip()
        assert abs(float(shown) - want) <= last_digit(shown) * (1 + 1e-9) + 1e-300, (
            f"{name}: {c['path']} shows {shown} for {want!r}")


def check_verdict(name, dom, sources):
    """The verdict is the page's first block, its numbers are the JSON's and the figure that
    shows it comes next; returns how many numbers it quotes."""
    m = VERDICT_FIRST.search(dom)
    assert m, f"{name}: the page does not open with its verdict: {dom[dom.find('<body'):][:600]}"
    key = KEY_FIGURE[name]
    after = dom[m.end():].lstrip()
    assert after.startswith(f'<figure id="{key}" data-figure="{key}">'), (
        f"{name}: the verdict is not followed by its figure {key}: {after[:300]}")
    v = Page()
    v.feed(m.group(1))
    v.close()
    assert any("path" in c for c in v.cells) or any("len" in c for c in v.cells), (
        f"{name}: the verdict quotes no number of the result: {m.group(1)[:400]}")
    check_cells(f"{name} verdict", v.cells, sources)
    return len(v.cells)


def check_report(name, html, sources, figures, shots):
    url = "file://" + os.path.abspath(html)
    with tempfile.TemporaryDirectory() as profile:
        p = subprocess.run(
            [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0",
             "--dump-dom", url],
            capture_output=True, text=True, timeout=180)
    assert p.returncode == 0, f"{name}: chromium failed: {p.stderr[-2000:]}"
    # Page messages are logged as CONSOLE lines; a failed resource load as net::ERR.
    bad = [l for l in p.stderr.splitlines() if "CONSOLE" in l or "net::ERR" in l]
    assert not bad, f"{name}: console output: {bad}"
    page = Page()
    page.feed(p.stdout)
    assert not page.forbidden, f"{name}: external resources {page.forbidden}"
    assert "<h1>" in p.stdout, f"{name}: the page did not render"
    for f in figures:
        assert f in page.figures, f"{name}: figure {f} missing ({list(page.figures)})"
        g = page.figures[f]
        assert g["svg"] and all(v and float(v) > 0 for v in g["svg"]), f"{name}: {f} has no size"
        assert g["elements"] > 30, f"{name}: {f} is nearly empty ({g['elements']} elements)"
    assert page.cells, f"{name}: no number cells"
    check_cells(name, page.cells, sources)
    verdict = check_verdict(name, p.stdout, sources)
    with tempfile.TemporaryDirectory() as profile:
        shot = os.path.join(shots, f"{name}.png")
        subprocess.run(
            [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--window-size=1000,1400",
             f"--screenshot={shot}", url],
            capture_output=True, text=True, timeout=180, check=True)
    w, h = png_size(shot)
    assert (w, h) == (1000, 1400), f"{name}: screenshot {w}x{h}"
    assert os.path.getsize(shot) > 20_000, f"{name}: blank screenshot"
    first = f", verdict first ({verdict} numbers) then {KEY_FIGURE[name]}"
    print(f"  {name}: {len(page.figures)} figures, {len(page.cells)} numbers equal to --json{first}, "
          f"screenshot {os.path.getsize(shot) // 1024} KiB")


CAMPAIGN = """[scenario]
name = "browser-campaign"
[scheme]
kind = "z-up-calibration"
lead_dwell_s = 120.0
dwell_s = 120.0
[sensor]
preset = "nav-grade-full"
[campaign]
from_c = 10.0
to_c = 50.0
runs = 5
"""

SWEEP = """[sweep]
name = "browser-sweep"
scenario = "builtin:paper-16pos-week"
duration_s = 3600.0
seeds = 2
outputs = ["lon_nm", "abs_lon_nm"]

[[parameter]]
key = "sensor.gyro.position_bias.dph[2]"
values = [0.0, 0.02]

[[parameter]]
key = "scheme.kind"
values = ["sixteen-position", "eight-position"]
"""

PAIRED = ["fig2_attitude_error", "fig3_position_error",
          "fig2_attitude_error_noise_free", "fig3_position_error_noise_free"]
MVM = ["residual_vs_temperature", "bias_by_position", "allan_residual", "navigation_error"]


def main():
    rins = os.path.abspath(sys.argv[1])
    t = tempfile.mkdtemp(prefix="rins-browser-")
    shots = os.environ.get("RINS_BROWSER_OUT", t)
    os.makedirs(shots, exist_ok=True)
    j = lambda cmd: json.loads(run([rins, *cmd]))
    checked = 0

    # The README's first command: the headline job always writes its report.
    quick = os.environ.get("RINS_BROWSER_QUICK") == "1"
    if not quick:
        run([rins, "paper", "--out", f"{t}/paper"])
        sources = {"analytic": j(["verify", "analytic", "--json"]),
                   "table4": json.load(open(f"{t}/paper/table4.json"))}
        check_report("paper", f"{t}/paper/report.html", sources, PAIRED, shots)
        checked += 1

    t4 = j(["paper", "table4", "--runs", "1", "--days", "0.05", "--json", "--out", f"{t}/t4",
            "--report", f"{t}/t4"])
    check_report("table4", f"{t}/t4/report.html", {"table4": t4}, PAIRED, shots)

    sea = j(["paper", "sea", "--runs", "1", "--days", "0.02", "--json", "--out", f"{t}/sea",
             "--report", f"{t}/sea"])
    check_report("sea", f"{t}/sea/report.html", {"sea": sea},
                 ["sea_horizontal_error", "sea_end_error"], shots)

    with open(f"{t}/camp.toml", "w") as f:
        f.write(CAMPAIGN)
    camp = j(["campaign", f"{t}/camp.toml", "--json", "--out", f"{t}/camp", "--report", f"{t}/camp"])
    check_report("campaign", f"{t}/camp/report.html", {"campaign": camp},
                 ["fig8_dbeta_vs_temperature"], shots)

    t5 = j(["paper", "table5", "--compensation", f"{t}/camp/dbeta-compensation.toml", "--runs", "1",
            "--days", "0.05", "--json", "--out", f"{t}/t5", "--report", f"{t}/t5"])
    check_report("table5", f"{t}/t5/report.html", {"table5": t5}, PAIRED, shots)

    cal = j(["calibrate", "builtin:calibration-z-down", "--json", "--out", f"{t}/cal",
             "--report", f"{t}/cal"])
    check_report("calibrate", f"{t}/cal/report.html", {"calibration": cal}, ["calibration_beta"], shots)

    run([rins, "measure", "docs/examples/diagnosis-truth.toml", "--out", f"{t}/unit.csv"])
    data = ["--model", "docs/examples/diagnosis-model.toml", "--data", f"{t}/unit.csv", "--json"]
    diag = j(["diagnose", *data, "--report", f"{t}/diag"])
    check_report("diagnose", f"{t}/diag/report.html", {"diagnose": diag}, MVM, shots)
    comp = j(["compare", *data, "--report", f"{t}/comp"])
    check_report("compare", f"{t}/comp/report.html", {"compare": comp}, MVM, shots)
    # --iterate on three missing effects: the history figure ("watch the error fall") and the
    # cell map before and after are on the page, its numbers equal to the --json history.
    run([rins, "measure", "docs/examples/three-effects-truth.toml", "--out", f"{t}/unit3.csv"])
    it = j(["diagnose", "--model", "docs/examples/diagnosis-model.toml", "--data", f"{t}/unit3.csv",
            "--iterate", "--out", f"{t}/iterated.toml", "--json", "--report", f"{t}/iter"])
    assert len(it["steps"]) >= 2, it["stop"]
    check_report("iterate", f"{t}/iter/report.html", {"iterate": it},
                 ["iteration_history", "cells_before_after"], shots)
    # A sweep with a numeric and a named key: its bands, swept values and per-seed figures.
    with open(f"{t}/sweep.toml", "w") as f:
        f.write(SWEEP)
    sw = j(["sweep", f"{t}/sweep.toml", "--json", "--out", f"{t}/sweep", "--report", f"{t}/sweep"])
    check_report("sweep", f"{t}/sweep/report.html", {"sweep": sw},
                 ["sweep_lon_nm", "sweep_abs_lon_nm"], shots)
    # The rotation schemes' analysis (every built-in scheme x every effect, well under a second).
    sch = j(["schemes", "analyse", "--json", "--report", f"{t}/schemes"])
    check_report("schemes", f"{t}/schemes/report.html", {"schemes": sch},
                 ["schemes_effects", "schemes_classes"], shots)
    checked += 10
    print(f"{checked} passed, 0 failed: HTML reports in headless Chromium")


if __name__ == "__main__":
    main()
