"""Case files in: TOML read and validated into a kind's model, and the one message a bad
case gets (the field, the value, what is allowed)."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path
from typing import Any

from pydantic import (
    BaseModel,
    ValidationError,
)

from .fields import SHOWN, CaseError, CaseInfo, cut_shown, shown
from .kinds import KINDS


def read_table(path: str | Path) -> dict:
    """A TOML file's table; a CaseError names the file where it cannot be read."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise CaseError(f"{path}: no such case file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise CaseError(f"{path}: cannot read it ({exc})") from None
    try:
        table = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"{path}: not valid TOML ({_toml_problem(exc, text)})") from None
    except RecursionError:
        raise CaseError(f"{path}: {TOO_DEEP}") from None
    if _depth(table) > MAX_DEPTH:
        raise CaseError(f"{path}: {TOO_DEEP}")
    return table


#: the deepest nesting of arrays and tables a case file may have (a case needs 4)
MAX_DEPTH = 16
TOO_DEEP = f"arrays or tables nested more than {MAX_DEPTH} deep (a case needs 4)"


def _depth(value, level: int = 0) -> int:
    """How deep arrays and tables nest in `value` (stops counting past MAX_DEPTH)."""
    if level > MAX_DEPTH or not isinstance(value, (dict, list)):
        return level
    children = value.values() if isinstance(value, dict) else value
    return max((_depth(v, level + 1) for v in children), default=level + 1)


def _toml_problem(exc: tomllib.TOMLDecodeError, text: str) -> str:
    """tomllib's message, with the key named where it says a value is given twice."""
    message = str(exc)
    at = re.search(r"at line (\d+)", message)
    if "Cannot overwrite" in message and at:
        key = text.splitlines()[int(at.group(1)) - 1].split("=", 1)[0].strip()
        return f"{key!r} is given twice ({message})"
    return message


def load_case(path: str | Path) -> tuple[CaseInfo, dict]:
    """Read and validate a case file; returns the model and the raw table (units as given)."""
    raw = read_table(path)
    return parse_case(raw, source=str(path), base=Path(path).parent), raw


def parse_case(raw: dict, source: str = "case", base: Path | None = None) -> CaseInfo:
    """Validate a case table (as read from TOML) into its kind's model; files it names are
    found relative to `base` (the case file's folder)."""
    if _depth(raw) > MAX_DEPTH:
        raise CaseError(f"{source}: {TOO_DEEP}")
    kind = raw.get("kind")
    allowed = ", ".join(KINDS)
    if kind is None:
        raise CaseError(f"{source}: kind: missing; allowed: {allowed}")
    if not isinstance(kind, str) or kind not in KINDS:
        raise CaseError(f"{source}: kind: {shown(kind)} is not a known kind; allowed: {allowed}")
    model = KINDS[kind]
    try:
        return model.model_validate(raw, context={"base": base})
    except ValidationError as exc:
        raise CaseError(f"{source}: {describe(exc, model)}") from None


def describe(exc: ValidationError, model: type[BaseModel]) -> str:
    """One line for the first validation error: field, value, what is allowed."""
    error = exc.errors(include_url=False)[0]
    field = _dotted(error["loc"])
    message = error["msg"].removeprefix("Value error, ")
    if error["type"] == "missing":
        hint = _field_description(model, error["loc"])
        return f"{field}: missing" + (f"; expected {hint}" if hint else "")
    if error["type"] == "extra_forbidden":
        return f"{field}: unknown field (check the spelling; see the README for each kind)"
    if not field:
        return message
    if error["type"] in ("value_error", "assertion_error") and (
            repr(error["input"]) in message or isinstance(error["input"], dict)):
        # a table's own check names its fields: the table itself is not repeated
        return f"{field}: {_shortened(message)}"
    return f"{field}: {shown(error['input'])}: {_shortened(message)}"


def _shortened(message: str) -> str:
    """A message with every long quoted value in it cut (see shown)."""
    return re.sub(rf"'[^']{{{SHOWN},}}'", lambda m: cut_shown(m.group(0)), message)


def _dotted(loc: tuple) -> str:
    out = ""
    for part in loc:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def _field_description(model: type[BaseModel], loc: tuple) -> str:
    current: Any = model
    info = None
    for part in loc:
        if isinstance(part, int) or not (isinstance(current, type) and issubclass(current, BaseModel)):
            continue
        info = current.model_fields.get(part)
        if info is None:
            return ""
        current = info.annotation
        args = getattr(current, "__args__", ())
        current = next((a for a in args if isinstance(a, type) and issubclass(a, BaseModel)), current)
    return (info.description or "") if info else ""
