"""Every file the package writes, whole or not at all: a file through a temporary file
beside it that is renamed onto it (write_atomic), a run's folder through a staging folder
that replaces it (staging_folder). Reports, plots, pictures, exports and sweep tables all
write here."""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path


def write_atomic(target: str | Path, write, binary: bool = False) -> Path:
    """Write a file whole or not at all: `write(handle)` fills a temporary file beside
    `target` (opened "wb" if binary, else UTF-8 text), which is then renamed onto it."""
    def fill(tmp: Path) -> None:
        with open(tmp, "wb") if binary else open(tmp, "w", encoding="utf-8") as handle:
            write(handle)

    return write_through_path(target, fill)


_STAGING = ".staging"


@contextlib.contextmanager
def staging_folder(target: str | Path):
    """Yield an empty folder beside `target` to write a run into; on success it replaces
    `target` (the old folder is renamed away first, then removed), on any failure it is
    removed and `target` stays as it was. Staging folders that a killed run left behind
    (their process gone) are removed on the way in."""
    target = Path(target).absolute()
    target.parent.mkdir(parents=True, exist_ok=True)
    _remove_abandoned(target)
    staging = Path(tempfile.mkdtemp(dir=target.parent,
                                    prefix=f".{target.name}.{os.getpid()}.", suffix=_STAGING))
    try:
        yield staging
        os.chmod(staging, 0o755)
        retired = None
        if target.exists():
            retired = staging.with_name(staging.name[:-len(_STAGING)] + ".retired")
            os.replace(target, retired)
        os.replace(staging, target)
        if retired is not None:
            shutil.rmtree(retired, ignore_errors=True)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise


def _remove_abandoned(target: Path) -> None:
    for folder in target.parent.glob(f".{target.name}.*.*"):
        if folder.suffix not in (_STAGING, ".retired"):
            continue
        pid = folder.name[len(target.name) + 2:].split(".")[0]
        if pid.isdigit() and not _alive(int(pid)):
            shutil.rmtree(folder, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def write_through_path(target: str | Path, write) -> Path:
    """Write a file whole or not at all where the writer needs a file name, not a handle
    (OCCT's STEP writer, trimesh's export): `write(path)` writes a temporary file beside
    `target`, which is then renamed onto it."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.",
                               suffix=".tmp" + target.suffix)
    os.close(fd)
    try:
        write(Path(tmp))
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target


def write_text(target: Path, text: str) -> Path:
    """Write a text file whole or not at all (write_atomic)."""
    return write_atomic(target, lambda handle: handle.write(text))
