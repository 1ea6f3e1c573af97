"""Partitioned VTK files for a distributed triangulation: one ``.vtu`` piece per block and a
``.pvtu`` that ParaView opens as one mesh. Inline base64 binary (the header, UInt64, encoded with
the data, as VTK's own writer does), written to a temporary name and renamed on success."""
import base64
import os

import numpy as np

_CELL_TYPE = {3: 5, 4: 10}  # VTK_TRIANGLE, VTK_TETRA


def _array(name: str, a: np.ndarray, vtk_type: str, components: int = 1) -> str:
    raw = np.ascontiguousarray(a).astype(a.dtype.newbyteorder("<"), copy=False).tobytes()
    text = base64.b64encode(np.array([len(raw)], dtype="<u8").tobytes() + raw).decode("ascii")
    attrs = f' Name="{name}"' if name else ""
    return (f'<DataArray type="{vtk_type}"{attrs} NumberOfComponents="{components}" '
            f'format="binary">{text}</DataArray>\n')


def _replace(path: str, text: str) -> None:
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="ascii") as f:
        f.write(text)
    os.replace(tmp, path)


def write_piece(path: str, points: np.ndarray, vertex_ids: np.ndarray, cells: np.ndarray,
                cell_ids: np.ndarray) -> None:
    """One piece: ``points`` (k, 2|3) with their global indices ``vertex_ids`` (sorted), and
    ``cells`` in global indices (renumbered into the piece's points here)."""
    k, d = points.shape
    pts3 = np.zeros((k, 3), dtype=np.float64)
    pts3[:, :d] = points
    conn = np.searchsorted(vertex_ids, cells).astype(np.int64)
    nv = cells.shape[1]
    offsets = np.arange(1, len(cells) + 1, dtype=np.int64) * nv
    types = np.full(len(cells), _CELL_TYPE[nv], dtype=np.uint8)
    text = (
        '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
        'byte_order="LittleEndian" header_type="UInt64">\n<UnstructuredGrid>\n'
        f'<Piece NumberOfPoints="{k}" NumberOfCells="{len(cells)}">\n'
        "<PointData>\n" + _array("global_id", vertex_ids.astype(np.int64), "Int64")
        + "</PointData>\n<CellData>\n" + _array("simplex_id", cell_ids.astype(np.int64), "Int64")
        + "</CellData>\n<Points>\n" + _array("", pts3, "Float64", 3)
        + "</Points>\n<Cells>\n" + _array("connectivity", conn.ravel(), "Int64")
        + _array("offsets", offsets, "Int64") + _array("types", types, "UInt8")
        + "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")
    _replace(path, text)


def write_index(path: str, pieces: list) -> None:
    """The ``.pvtu`` over ``pieces`` (file names relative to its folder)."""
    lines = [
        '<?xml version="1.0"?>',
        '<VTKFile type="PUnstructuredGrid" version="1.0" byte_order="LittleEndian" '
        'header_type="UInt64">',
        '<PUnstructuredGrid GhostLevel="0">',
        '<PPointData><PDataArray type="Int64" Name="global_id"/></PPointData>',
        '<PCellData><PDataArray type="Int64" Name="simplex_id"/></PCellData>',
        '<PPoints><PDataArray type="Float64" NumberOfComponents="3"/></PPoints>',
    ] + [f'<Piece Source="{p}"/>' for p in pieces] + ["</PUnstructuredGrid>", "</VTKFile>", ""]
    _replace(path, "\n".join(lines))
