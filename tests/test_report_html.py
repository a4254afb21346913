"""report.html and report.md from their templates: one self-contained page (pictures
embedded, nothing fetched), key results first, then the design checks (failed ones flagged)
apart from the source-data notes, human labels and rounded numbers, the positions collapsed,
the inputs as given; the page loads in a headless Chromium when one is installed (CI
installs Debian's), and its result tables sort by a clicked column."""

import base64
import re
import shutil
import subprocess

import pytest

from toothcontact.views import report


def png() -> bytes:
    """A small real PNG (red square)."""
    from io import BytesIO

    from PIL import Image

    out = BytesIO()
    Image.new("RGB", (40, 30), (214, 39, 40)).save(out, format="png")
    return out.getvalue()


PNG = png()


def document() -> dict:
    return {
        "case": "demo", "kind": "spur", "title": "A <pair> & its teeth", "source": "a test",
        "assumptions": ["steel on steel"], "toothcontact_version": "0", "units": "mm, N, MPa",
        "inputs": {"kind": "spur", "face_width": "30 mm", "load": {"tangential_load": "8000 N"}},
        "summary": {"max_p_max_MPa": 1993.2, "load_sharing": "equal split"},
        "positions": [{"roll_deg": -9.0, "pair": 0, "edge_margins_mm": {"pinion_tip": -0.2}},
                      {"roll_deg": 0.0, "pair": 0, "edge_margins_mm": {}}],
        "ease_off": {"separation_um": [[1.0, None], [2.0, 3.0]] * 10},
        "checks": [{"name": "stress within the allowable", "ok": True, "detail": "1993 < 2000",
                    "kind": "design"},
                   {"name": "contact ellipse clear of the tip", "ok": False,
                    "detail": "worst margin -0.2 mm", "kind": "design"},
                   {"name": "published eta_tot at -20 °C equals eta_z·eta_spindle", "ok": False,
                    "detail": "the source's column is inconsistent", "kind": "source"}],
        "notes": ["crown measured along the flank normal"],
    }


@pytest.fixture
def images(tmp_path):
    paths = [tmp_path / "pattern_head_on.png", tmp_path / "mesh_cycle.png"]
    for p in paths:
        p.write_bytes(PNG)
    return paths


def test_html_is_self_contained_key_results_and_failed_checks_first(images):
    page = report.html(document(), images)
    assert page.startswith("<!DOCTYPE html>")
    # nothing is fetched: no external address, stylesheet link or script file; the one
    # script is inline (the tables' sorting)
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:|//|file:)""", page)
    assert "<link" not in page and "@import" not in page
    assert re.findall(r"<script[^>]*>", page) == ["<script>"]
    # every picture embedded, as data
    assert page.count('src="data:image/png;base64,') == len(images)
    assert base64.b64encode(PNG).decode() in page
    # key results, then the failed design check, then pictures, results, inputs
    key = page.index("Key results")
    failed = page.index("contact ellipse clear of the tip")
    assert key < failed < page.index("<img") < page.index('id="results"') < page.index("Inputs (as given)")
    assert "1 of 2 design checks failed" in page
    assert "largest Hertz pressure" in page and "1993 MPa" in page
    # the source's inconsistency is a note of its own, not a failed design check
    source = page.index("published eta_tot at -20")
    assert source > page.index("Source data and method") > page.index('id="results"')
    # human labels with units; the positions table collapsed
    assert "pinion roll [deg]" in page and "roll_deg" not in page
    assert "<details><summary>" not in page or "positions" in page
    # inputs with their units as given (no escaped unicode, no empty table headers),
    # assumptions of the case and of the tool
    assert "30 mm" in page and "8000 N" in page and "[load]" in page
    assert "steel on steel" in page and "equal split" in page and "flank normal" in page
    # text is escaped
    assert "A &lt;pair&gt; &amp; its teeth" in page and "<pair>" not in page


def test_markdown_holds_no_giant_line_and_names_the_pictures(images):
    """The ease-off matrix is summarised, not dumped; every line stays readable."""
    text = report.markdown(document(), [p.name for p in images])
    assert max(len(line) for line in text.splitlines()) < 2000
    assert "[20 × 2 values, 1 to 3]" in text
    assert text.index("## Key results") < text.index("## Design checks") < text.index("## Results")
    assert "(mesh_cycle.png)" in text and "\n\n\n" not in text


def test_inputs_are_shown_as_given():
    """Unicode stays itself, a table holding only sub-tables gets no empty header."""
    from toothcontact.views.report_view import toml_lines

    lines = toml_lines({"title": "z = 20 × 60", "pinion": {"crown": {"height": "10 um"}}})
    assert lines[0] == 'title = "z = 20 × 60"'
    assert "[pinion]" not in lines and "[pinion.crown]" in lines


def test_labels_and_numbers_read_as_an_engineer_writes_them():
    from toothcontact.views.labels import label, number

    assert label("face_position_mm") == "position along the face [mm]"
    assert label("loaded_transmission_error_urad") == "transmission error (loaded) [µrad]"
    assert label("normal_backlash_mm") == "normal backlash [mm]"
    assert label("viscosity_mm2_s") == "viscosity [mm²/s]"
    assert number(1.96638e-08) == "1.966e-08" and number(1.96638e-08, scale=3.0) == "0"
    # beside its column's largest (1.417 mm, shown to 0.001 mm) a figure below half that
    # resolution is 0, one above it keeps its digits; large numbers in digits
    assert number(6.839e-06, scale=1.417) == "0" and number(0.0002052, scale=42.5) == "0"
    assert number(-0.0006, scale=1.417) == "-0.0006" and number(-0.0004, scale=1.417) == "0"
    assert number(30000.0) == "30000" and number(123456.0) == "123500"
    assert number(9999.6) == "10000" and number(2.5e12) == "2.5e+12"
    assert number(3265.9474) == "3266" and number(True) == "yes" and number(None) == ""
    assert number({"pinion_tip": -0.2}) == "pinion_tip: -0.2"


def test_a_column_that_applies_to_no_row_is_left_out():
    """A result table drops a column whose every row is null (the Kim case's temperature
    and viscosity: it has no lubricant conditions) and keeps the others in their order."""
    from toothcontact.views.report_view import _tables

    table, = _tables("efficiency", [{"temperature_C": None, "mu_zm": 0.029, "eta_z": 0.8553},
                                    {"temperature_C": None, "mu_zm": None, "eta_z": 0.9}],
                     "worm_efficiency")
    assert table.headers == ["mean friction mu_zm", "efficiency eta_z (worm driving)"]
    assert table.rows == [["0.029", "0.8553"], ["", "0.9"]]


def test_write_run_writes_the_html_beside_the_markdown(images, tmp_path):
    written = report.write_run(tmp_path, document(), images)
    assert [p.name for p in written] == ["result.json", "report.md", "report.html"]
    md = (tmp_path / "report.md").read_text()
    assert "![" in md and "(pattern_head_on.png)" in md
    assert not list(tmp_path.glob(".*.tmp"))


def chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        found = shutil.which(name)
        if found:
            return found
    return None


def browser_flags(tmp_path, *extra: str) -> list[str]:
    """Headless Chromium's flags for a test page: no network, a fresh profile in
    `tmp_path`, the page's console on stderr, 5 s of virtual time for its scripts."""
    return ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            f"--user-data-dir={tmp_path / 'profile'}", "--enable-logging=stderr", "--v=0",
            "--virtual-time-budget=5000", *extra]


def dump_dom(text: str, script: str, tmp_path, *extra: str) -> subprocess.CompletedProcess:
    """The page `text` as Chromium leaves it after load, `script` added before </body>
    (a probe that writes what it finds into the DOM): the finished process, its DOM on
    stdout."""
    probe = tmp_path / "probe.html"
    probe.write_text(text.replace("</body>", f"<script>{script}</script></body>"),
                     encoding="utf-8")
    return subprocess.run([chromium(), *browser_flags(tmp_path, *extra), "--dump-dom",
                           probe.as_uri()], capture_output=True, text=True, timeout=120,
                          check=False)


@pytest.mark.skipif(chromium() is None, reason="no Chromium installed")
def test_the_page_loads_in_headless_chromium(images, tmp_path):
    """The page as a browser shows it: its DOM after load (a probe script added to a test
    copy reports every image's decoded size: each must have loaded) and a screenshot that is
    not blank (many distinct colours, text and pictures)."""
    from PIL import Image

    page = tmp_path / "report.html"
    text = report.html(document(), images)
    page.write_text(text, encoding="utf-8")
    done = dump_dom(text, """
addEventListener("load", () => { const p = document.createElement("p"); p.id = "probe";
p.textContent = [...document.images].map(i => i.complete + ":" + i.naturalWidth).join(",");
document.body.append(p); });""", tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    dom = done.stdout
    assert "1 of 2 design checks failed" in dom and dom.count("<img") == len(images)
    loaded = re.search(r'<p id="probe">([^<]*)</p>', dom).group(1).split(",")
    assert loaded == ["true:40"] * len(images)
    # no console error from the page itself (Chromium's own messages about its sandbox,
    # D-Bus and the like are not the page's)
    assert "Uncaught" not in done.stderr and "CONSOLE(" not in done.stderr
    shot = tmp_path / "shot.png"
    subprocess.run([chromium(), *browser_flags(tmp_path), f"--screenshot={shot}",
                    "--window-size=1200,1600",
                    page.as_uri()], capture_output=True, text=True, timeout=120, check=True)
    image = Image.open(shot).convert("RGB")
    assert image.size == (1200, 1600)
    colours = image.getcolors(maxcolors=1 << 20)
    assert len(colours) > 50                             # text, boxes and the red pictures
    assert sum(n for n, c in colours if c == (214, 39, 40)) > 40 * 30 / 2   # a picture shows


@pytest.mark.skipif(chromium() is None, reason="no Chromium installed")
def test_no_text_overflows_the_page_in_a_browser(tmp_path):
    """A real report (the bundled relieved spur pair: its load distribution's note, the
    transmission error's arm, long texts in value columns) in a 1000 px wide window: the
    page never scrolls sideways, and every table of quantities fits its box (only a wide
    table of many columns may scroll inside its own frame); a long text in a number column
    wraps."""
    from toothcontact import runner

    document = runner.analyse_file(runner.bundled_cases_dir() / "spur_relieved_20_60.toml")
    text = report.html(document, [])
    assert "line loads along the pinion" in text
    done = dump_dom(text, """
addEventListener("load", () => { const root = document.documentElement;
const wide = [...document.querySelectorAll("div.wide")].filter(d =>
  d.querySelector("tr").children.length <= 2 && d.scrollWidth > d.clientWidth + 1);
const p = document.createElement("p"); p.id = "probe";
p.textContent = root.scrollWidth + ":" + root.clientWidth + ":" + wide.length;
document.body.append(p); });""", tmp_path, "--window-size=1000,1400")
    assert done.returncode == 0, done.stderr[-2000:]
    scroll, client, overflowing = map(int, re.search(r'<p id="probe">([^<]*)</p>',
                                                     done.stdout).group(1).split(":"))
    assert scroll <= client and overflowing == 0


@pytest.mark.skipif(chromium() is None, reason="no Chromium installed")
def test_a_result_table_sorts_by_the_column_clicked(tmp_path):
    """In a headless Chromium, the positions table (roll -9° and 0°) clicked on its roll
    header sorts ascending, then descending, the header marked (the page's own inline
    script; no console error)."""
    text = report.html(document(), [])
    done = dump_dom(text, """
addEventListener("load", () => {
  const table = [...document.querySelectorAll("table.sortable")].find(t =>
    [...t.rows[0].cells].some(c => c.textContent.includes("roll")));
  const th = [...table.rows[0].cells].find(c => c.textContent.includes("roll"));
  const column = [...table.rows[0].cells].indexOf(th);
  const read = () => [...table.rows].slice(1).map(r => r.cells[column].textContent).join("|");
  th.click(); const up = read() + "/" + th.getAttribute("aria-sort");
  th.click(); const down = read() + "/" + th.getAttribute("aria-sort");
  const p = document.createElement("p"); p.id = "probe"; p.textContent = up + ";" + down;
  document.body.append(p); });""", tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    found = re.search(r'<p id="probe">([^<]*)</p>', done.stdout).group(1)
    up, down = found.split(";")
    assert up.endswith("/ascending") and down.endswith("/descending")
    values = [float(v.replace("\u2212", "-")) for v in up.split("/")[0].split("|")]
    assert values == sorted(values) and len(values) == 2
    assert down.split("/")[0].split("|") == up.split("/")[0].split("|")[::-1]
    assert "Uncaught" not in done.stderr
