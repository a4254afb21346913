"""The README documents every case field the bundled cases use (issue 13, item 8): each
key of every bundled case appears as a word inside a code span or block of the README."""

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
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    fenced = re.findall(r"```.*?```", readme, re.S)
    prose = re.sub(r"```.*?```", " ", readme, flags=re.S)
    spans = " ".join(fenced + re.findall(r"`([^`]+)`", prose))
    words = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", spans))
    undocumented = sorted({path for case in sorted((ROOT / "cases").glob("*.toml"))
                           for path, key in keys(tomllib.loads(case.read_text()))
                           if key not in words})
    assert not undocumented, f"README lacks: {undocumented}"
