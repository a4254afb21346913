"""The optional parts of the install and what a missing one says.

The core install analyses every case kind and writes results, reports and plots. Three
extras add the rest: `cad` (OCP: STEP export and STEP input), `viz` (pyvista/VTK: the 3D
pictures) and `sweep` (Dask, pyarrow, SALib: tolerance sweeps; pandas: the API's tables);
`all` holds the three."""

from __future__ import annotations

#: the top-level module -> the extra that installs it
EXTRA_OF = {"OCP": "cad", "cadquery": "cad", "pyvista": "viz", "vtk": "viz",
            "vtkmodules": "viz", "dask": "sweep", "distributed": "sweep", "pyarrow": "sweep",
            "SALib": "sweep", "pandas": "sweep"}


def missing_extra(exc: BaseException) -> str | None:
    """What to install when `exc` is a missing module of an extra, else None."""
    if not isinstance(exc, ModuleNotFoundError) or not exc.name:
        return None
    extra = EXTRA_OF.get(exc.name.split(".")[0])
    if extra is None:
        return None
    return (f"this needs the {extra} extra ({exc.name} is not installed): "
            f"pip install 'toothcontact[{extra}]', or '[all]'")


def installed(extra: str) -> bool:
    """Whether every module of `extra` can be imported here."""
    from importlib.util import find_spec

    return all(find_spec(module) is not None for module, owner in EXTRA_OF.items()
               if owner == extra and module not in ("cadquery", "vtk", "vtkmodules"))
