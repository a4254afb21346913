"""Files and checks of solids: validity, volume, STEP write/read, tessellation and STL.

All writes go through a temporary file that is renamed into place. OCP is imported lazily.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np


def is_valid(shape) -> bool:
    from OCP.BRepCheck import BRepCheck_Analyzer

    return bool(BRepCheck_Analyzer(shape).IsValid())


def volume(shape) -> float:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


def _quiet_occt() -> None:
    """Keep OCCT's transfer statistics off the terminal (errors still show)."""
    from OCP.Message import Message, Message_Gravity

    printers = Message.DefaultMessenger_s().Printers()
    for i in range(printers.Lower(), printers.Upper() + 1):
        printers.Value(i).SetTraceLevel(Message_Gravity.Message_Fail)


def write_step(shape, path: Path) -> Path:
    """Write a STEP file through a temporary file (no half-written output)."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    from ..writing import write_through_path

    _quiet_occt()
    writer = STEPControl_Writer()
    writer.Transfer(shape, STEPControl_AsIs)

    def write(tmp: Path) -> None:
        if writer.Write(str(tmp)) != IFSelect_RetDone:
            raise RuntimeError(f"could not write {path}")

    return write_through_path(path, write)


def read_step(path: Path):
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader

    _quiet_occt()
    reader = STEPControl_Reader()
    if reader.ReadFile(str(path)) != IFSelect_RetDone:
        raise ValueError(f"{path}: not a readable STEP file")
    reader.TransferRoots()
    shape = reader.OneShape()
    if shape is None or shape.IsNull() or not _has_faces(shape):
        raise ValueError(f"{path.name} holds no solid or surface (a STEP file with no "
                         "geometry in its DATA section)")
    return shape


def _has_faces(shape) -> bool:
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer

    return TopExp_Explorer(shape, TopAbs_FACE).More()


def tessellate(shape, tolerance: float = 0.005, angular: float = 0.2):
    """Triangles of a shape: (vertices (n, 3), faces (m, 3)), vertices merged."""
    import trimesh
    from OCP.BRep import BRep_Tool
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS

    BRepMesh_IncrementalMesh(shape, tolerance, False, angular, True)
    vertices, faces, offset = [], [], 0
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        face = TopoDS.Face_s(explorer.Current())
        location = TopLoc_Location()
        triangulation = BRep_Tool.Triangulation_s(face, location)
        explorer.Next()
        if triangulation is None:
            continue
        transform = location.Transformation()
        nodes = np.array([[*(lambda p: (p.X(), p.Y(), p.Z()))(
            triangulation.Node(i).Transformed(transform))] for i in range(1, triangulation.NbNodes() + 1)])
        tris = np.array([triangulation.Triangle(i).Get()
                         for i in range(1, triangulation.NbTriangles() + 1)]) - 1
        if face.Orientation() == TopAbs_REVERSED:
            tris = tris[:, ::-1]
        vertices.append(nodes)
        faces.append(tris + offset)
        offset += len(nodes)
    mesh = trimesh.Trimesh(np.concatenate(vertices), np.concatenate(faces), process=True)
    mesh.merge_vertices(digits_vertex=7)
    return mesh


def write_mesh(mesh, path: Path) -> Path:
    """Write a trimesh mesh as binary STL through a temporary file."""
    from ..writing import write_through_path

    return write_through_path(path, lambda tmp: mesh.export(tmp, file_type="stl"))
