"""A sweep's records on disk: one Parquet file per finished sample under OUT/parts
(written whole or not at all by writing.write_atomic), so a killed sweep loses nothing and
a resumed one knows what is done; the sweep's table (samples.parquet) stacks them in
sample order."""

from __future__ import annotations

import shutil
from pathlib import Path

PARTS = "parts"


def _part(out: Path, sample: int, what: str = "sample") -> Path:
    return Path(out) / PARTS / f"{what}_{sample:07d}.parquet"


def finished(out: Path, positions: bool = False) -> set[int]:
    """The sample numbers already checkpointed in `out` (with their rows per position, if
    `positions`)."""
    def numbers(what):
        return {int(p.stem.split("_")[1]) for p in (Path(out) / PARTS).glob(f"{what}_*.parquet")}

    done = numbers("sample")
    return done & numbers("positions") if positions else done


def clear(out: Path) -> set[int]:
    """Forget the checkpoints of an earlier sweep in `out`; nothing is finished."""
    shutil.rmtree(Path(out) / PARTS, ignore_errors=True)
    return set()


def write_part(out: Path, record: dict, positions: list[dict] | None = None) -> None:
    """Checkpoint one sample's record (and its rows per position, when kept: written
    first, so a sample's record marks it done only with its rows in place)."""
    if positions is not None:
        write_table(_part(out, record["sample"], "positions"), positions)
    write_table(_part(out, record["sample"]), [record])


def records(out: Path, samples: list[int]) -> list[dict]:
    """The checkpointed records of the given samples, in sample order (a sample without a
    checkpoint is left out)."""
    import pyarrow.parquet as pq

    out = Path(out)
    return [pq.read_table(_part(out, k)).to_pylist()[0] for k in sorted(samples)
            if _part(out, k).is_file()]


def position_rows(out: Path, samples: list[int]) -> list[dict]:
    """The checkpointed rows per position of the given samples, in sample order."""
    import pyarrow.parquet as pq

    out = Path(out)
    return [row for k in sorted(samples) if _part(out, k, "positions").is_file()
            for row in pq.read_table(_part(out, k, "positions")).to_pylist()]


def write_table(target: Path, rows: list[dict]) -> Path:
    """The sweep's table: one row per record, the columns the union of theirs (null where a
    record has none), written whole or not at all."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from ..writing import write_atomic

    columns = list(dict.fromkeys(key for row in rows for key in row))
    table = (pa.Table.from_pylist([{key: row.get(key) for key in columns} for row in rows])
             if rows else pa.table({}))
    return write_atomic(target, lambda handle: pq.write_table(table, handle), binary=True)
