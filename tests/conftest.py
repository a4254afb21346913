"""Shared test helpers."""

import subprocess
import sys

import pytest


@pytest.fixture
def fresh_python():
    """Run Python code in a new interpreter (nothing imported yet) and return the last line
    it prints: for checks on which modules a code path loads."""
    def run(code: str) -> str:
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        return out.stdout.strip().splitlines()[-1]
    return run
