#!/usr/bin/env python3
"""Writes the .vtu fixtures of test_io with Python's own struct, base64 and zlib modules (an
implementation independent of gpugeom's), in every encoding VTK files come in: ascii, inline
base64 with the header encoded apart (VTK) or together (meshio), appended raw and base64, zlib
in several blocks, 32- and 64-bit headers, big endian, 32-bit floats and 64-bit integers.
Each file also carries point data (Float64) and cell data (Int32, and Float32 with 3
components), as the arrays programs attach to meshes.
Run from this folder: python3 make_vtu_fixtures.py (writes data/*.vtu)."""
import base64
import struct
import zlib

TRI_POINTS = [(0.1, -2.5e-7, 0.0), (3.0, 0.25, 0.0), (-1.5, 7.0, 0.0), (2.0, 2.0, 0.0)]
TRI_CELLS = [(0, 1, 2), (1, 3, 2)]
TET_POINTS = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1.5)]
TET_CELLS = [(0, 1, 2, 3), (1, 2, 3, 4)]

FMT = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "UInt8": "B"}


def raw(values, typ, big):
    return struct.pack(("<" if not big else ">") + FMT[typ] * len(values), *values)


def word(v, header, big):
    return struct.pack(("<" if not big else ">") + ("I" if header == 4 else "Q"), v)


def block(data, header, big, zblock):
    """Header and data bytes of one array (zblock: zlib block size, or None)."""
    if zblock is None:
        return word(len(data), header, big), data
    parts = [data[i : i + zblock] for i in range(0, len(data), zblock)] or [b""]
    comp = [zlib.compress(p) for p in parts]
    last = len(parts[-1]) if len(parts[-1]) != zblock else 0
    head = word(len(parts), header, big) + word(zblock, header, big) + word(last, header, big)
    head += b"".join(word(len(c), header, big) for c in comp)
    return head, b"".join(comp)


def write(path, points, cells, fmt, header=4, big=False, zblock=None, joint=False,
          ptype="Float64", itype="Int64"):
    k = len(cells[0])
    # Point data (a height per point) and cell data (a region number and a 3-component
    # float32 vector per cell), as the arrays a program attaches.
    sections = [
        ("PointData", [("height", "Float64", 1, [0.5 * i - 1.25 for i in range(len(points))])]),
        ("CellData", [("region", "Int32", 1, [7 * i - 3 for i in range(len(cells))]),
                      ("normal", "Float32", 3, [0.5, -1.0, 2.0] * len(cells))]),
        ("Points", [("", ptype, 3, [c for p in points for c in p])]),
        ("Cells", [("connectivity", itype, 1, [v for c in cells for v in c]),
                   ("offsets", itype, 1, [k * (i + 1) for i in range(len(cells))]),
                   ("types", "UInt8", 1, [5 if k == 3 else 10] * len(cells))]),
    ]
    attrs = 'type="UnstructuredGrid" version="1.0" byte_order="%s"' % (
        "BigEndian" if big else "LittleEndian")
    if fmt != "ascii":
        attrs += ' header_type="%s"' % ("UInt32" if header == 4 else "UInt64")
    if zblock is not None:
        attrs += ' compressor="vtkZLibDataCompressor"'
    OFFSET[0] = 0
    out = ['<?xml version="1.0"?>\n<VTKFile %s>\n<UnstructuredGrid>\n' % attrs,
           '<Piece NumberOfPoints="%d" NumberOfCells="%d">\n' % (len(points), len(cells))]
    appended = b""
    for sec, arrays in sections:
        parts = []
        out.append("<%s>\n" % sec)
        append_arrays(out, arrays, fmt, header, big, zblock, joint, parts)
        out.append("</%s>\n" % sec)
        appended += b"".join(parts)
    out.append("</Piece>\n</UnstructuredGrid>\n")
    body = "".join(out).encode()
    if fmt in ("raw", "base64"):
        body += b'<AppendedData encoding="%s">\n_' % fmt.encode() + appended
        body += b"\n</AppendedData>\n"
    body += b"</VTKFile>\n"
    with open(path, "wb") as f:
        f.write(body)


OFFSET = [0]  # where the next appended array starts (in bytes or base64 characters)


def append_arrays(out, arrays, fmt, header, big, zblock, joint, appended_parts):
    for name, typ, comps, values in arrays:
        tag = '<DataArray type="%s"%s NumberOfComponents="%d" ' % (
            typ, ' Name="%s"' % name if name else "", comps)
        if fmt == "ascii":
            out.append(tag + 'format="ascii">\n' + " ".join(repr(v) for v in values) +
                       "\n</DataArray>\n")
            continue
        head, data = block(raw(values, typ, big), header, big, zblock)
        if fmt == "binary":
            text = (base64.b64encode(head + data) if joint else
                    base64.b64encode(head) + base64.b64encode(data)).decode()
            out.append(tag + 'format="binary">\n' + text + "\n</DataArray>\n")
        else:
            if fmt == "base64":
                chunk = base64.b64encode(head) + base64.b64encode(data)
            else:
                chunk = head + data
            out.append(tag + 'format="appended" offset="%d"/>\n' % OFFSET[0])
            appended_parts.append(chunk)
            OFFSET[0] += len(chunk)


T, TC, P, PC = TRI_POINTS, TRI_CELLS, TET_POINTS, TET_CELLS
write("data/tri_ascii.vtu", T, TC, "ascii")
write("data/tri_inline_u32_apart.vtu", T, TC, "binary", header=4, itype="Int32")
write("data/tri_inline_u64_joint_f32.vtu", T, TC, "binary", header=8, joint=True,
      ptype="Float32")
write("data/tri_inline_zlib_u32.vtu", T, TC, "binary", header=4, zblock=16)
write("data/tri_inline_zlib_u64_joint.vtu", T, TC, "binary", header=8, zblock=40, joint=True)
write("data/tri_appended_raw_u32.vtu", T, TC, "raw", header=4)
write("data/tri_appended_raw_zlib_u64.vtu", T, TC, "raw", header=8, zblock=24)
write("data/tri_appended_base64_u64.vtu", T, TC, "base64", header=8)
write("data/tri_appended_base64_zlib_u32.vtu", T, TC, "base64", header=4, zblock=20)
write("data/tri_appended_raw_big.vtu", T, TC, "raw", header=4, big=True)
write("data/tet_appended_raw_zlib_u64.vtu", P, PC, "raw", header=8, zblock=32)
write("data/tet_inline_big_u64.vtu", P, PC, "binary", header=8, big=True)
