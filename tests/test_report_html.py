"""report.html: one self-contained page (pictures embedded, nothing fetched), failed checks
first; it loads in a headless Chromium when one is installed."""

import base64
import re
import shutil
import subprocess

import pytest

from toothcontact import report



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
        "checks": [{"name": "stress within the allowable", "ok": True, "detail": "1993 < 2000"},
                   {"name": "contact ellipse clear of the tip", "ok": False,
                    "detail": "worst margin -0.2 mm"}],
        "notes": ["crown measured along the flank normal"],
    }


@pytest.fixture
def images(tmp_path):
    paths = [tmp_path / "pattern_head_on.png", tmp_path / "mesh_cycle.png"]
    for p in paths:
        p.write_bytes(PNG)
    return paths


def test_html_is_self_contained_with_the_failed_checks_first(images):
    page = report.html(document(), images)
    assert page.startswith("<!DOCTYPE html>")
    # nothing is fetched: no external address, stylesheet link or script
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:|//|file:)""", page)
    assert "<link" not in page and "<script" not in page and "@import" not in page
    # every picture embedded, as data
    assert page.count('src="data:image/png;base64,') == len(images)
    assert base64.b64encode(PNG).decode() in page
    # the failed check comes before everything else that reports
    failed = page.index("contact ellipse clear of the tip")
    assert failed < page.index("Inputs (as given)") < page.index("Results")
    assert failed < page.index("<img")
    assert "Failed checks (1 of 2)" in page
    # inputs with their units as given, assumptions of the case and of the tool
    assert "30 mm" in page and "8000 N" in page
    assert "steel on steel" in page and "equal split" in page and "flank normal" in page
    # text is escaped
    assert "A &lt;pair&gt; &amp; its teeth" in page and "<pair>" not in page


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


@pytest.mark.skipif(chromium() is None, reason="no Chromium installed")
def test_the_page_loads_in_headless_chromium(images, tmp_path):
    page = tmp_path / "report.html"
    page.write_text(report.html(document(), images), encoding="utf-8")
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             f"--user-data-dir={tmp_path / 'profile'}", "--enable-logging=stderr", "--v=0"]
    done = subprocess.run([chromium(), *flags, "--dump-dom", page.as_uri()],
                          capture_output=True, text=True, timeout=120, check=False)
    assert done.returncode == 0, done.stderr[-2000:]
    dom = done.stdout
    assert "Failed checks (1 of 2)" in dom and dom.count("<img") == len(images)
    # no console error from the page itself (Chromium's own messages about its sandbox,
    # D-Bus and the like are not the page's)
    assert "Uncaught" not in done.stderr and "CONSOLE(" not in done.stderr
    shot = tmp_path / "shot.png"
    subprocess.run([chromium(), *flags, f"--screenshot={shot}", "--window-size=1200,1600",
                    page.as_uri()], capture_output=True, text=True, timeout=120, check=True)
    assert shot.stat().st_size > 10_000
