"""The user guide documents every case field the bundled cases use (issue 13, item 8): each
key of every bundled case appears as a word inside a code span or block of
docs/user-guide.md (the README, which a newcomer reads in ten minutes, points there); and
the README keeps what a newcomer needs: the two commands, a case file, what comes out."""

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).parents[1]


def keys(table: dict, prefix: str = ""):
    for key, value in table.items():
        yield prefix + key, key
        if isinstance(value, dict):
            yield from keys(value, f"{prefix}{key}.")
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            for row in value:
                yield from keys(row, f"{prefix}{key}[].")


def test_every_field_of_the_bundled_cases_is_documented():
    readme = (ROOT / "docs" / "user-guide.md").read_text(encoding="utf-8")
    fenced = re.findall(r"```.*?```", readme, re.S)
    prose = re.sub(r"```.*?```", " ", readme, flags=re.S)
    spans = " ".join(fenced + re.findall(r"`([^`]+)`", prose))
    words = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", spans))
    undocumented = sorted({path for case in sorted((ROOT / "cases").glob("*.toml"))
                           for path, key in keys(tomllib.loads(case.read_text()))
                           if key not in words})
    assert not undocumented, f"docs/user-guide.md lacks: {undocumented}"


def test_the_readme_is_a_newcomers_page():
    """Short (at most 200 lines), the Quick start's two commands, a bundled case file as it
    is, what a run writes, and where to read on."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme.splitlines()) <= 200
    block = re.search(r"## Quick start.*?```bash\n(.*?)```", readme, re.S).group(1)
    assert len([line for line in block.splitlines() if line.strip()]) == 2
    case = (ROOT / "cases" / "spur_crowned_20_60.toml").read_text(encoding="utf-8").strip()
    assert case in readme
    for name in ("result.json", "report.html", "positions.csv", "docs/user-guide.md",
                 "docs/DESIGN.md"):
        assert name in readme
