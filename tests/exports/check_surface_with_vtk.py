#!/usr/bin/env python3
"""Reads sphclip's surface export (--export surface, binary PLY) with VTK's
own reader (vtkPLYReader, Debian python3-vtk9), an implementation independent
of sphclip's writer: as many points and triangles as the header says, unit
normals, a colour per vertex, every point inside the scene's domain; the
colour field's values (a property VTK's reader skips) are read with Python's
struct module and checked against the same run's particle speeds. A 3D scene
(OpenVDB builds only) and a 2D one. Exits 77 (ctest's "skipped") when VTK's
Python module is absent.

usage: check_surface_with_vtk.py PATH/TO/sphclip SOURCE_DIR"""
import csv
import math
import os
import struct
import tempfile

from vtk_checks import check, finish, vtk
import vtk_checks


def run(scene, out, extra, duration="0.04"):
    return vtk_checks.run(scene, out, ["--export", "surface", "--export", "csv"] + extra,
                          duration, capture_output=True, text=True)


def read_header(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    counts, props = {}, []
    for line in header:
        words = line.split()
        if words[0] == "element":
            counts[words[1]] = int(words[2])
        elif words[0] == "property" and words[1] != "list":
            props.append((words[1], words[2]))
    return header, counts, props, data[end:]


def check_ply(path, domain_min, domain_max, speeds):
    header, counts, props, body = read_header(path)
    check(header[1] == "format binary_little_endian 1.0", f"{path}: not binary little-endian")
    reader = vtk.vtkPLYReader()
    reader.SetFileName(path)
    reader.Update()
    mesh = reader.GetOutput()
    n = mesh.GetNumberOfPoints()
    check(n == counts["vertex"] and n > 0, f"{path}: VTK read {n} points, header {counts['vertex']}")
    check(mesh.GetNumberOfCells() == counts["face"],
          f"{path}: VTK read {mesh.GetNumberOfCells()} cells, header {counts['face']}")
    for c in range(0, mesh.GetNumberOfCells(), max(1, mesh.GetNumberOfCells() // 200)):
        check(mesh.GetCell(c).GetNumberOfPoints() == 3, f"{path}: cell {c} is not a triangle")
    normals = mesh.GetPointData().GetNormals()
    rgb = mesh.GetPointData().GetArray("RGB")
    check(normals is not None and rgb is not None, f"{path}: VTK found no normals or colours")
    lo = [min(mesh.GetPoint(i)[a] for i in range(n)) for a in range(3)]
    hi = [max(mesh.GetPoint(i)[a] for i in range(n)) for a in range(3)]
    for a in range(len(domain_min)):
        size = domain_max[a] - domain_min[a]
        check(lo[a] >= domain_min[a] - 0.05 * size and hi[a] <= domain_max[a] + 0.05 * size,
              f"{path}: points outside the domain on axis {a}: {lo[a]} .. {hi[a]}")
    if normals is not None:
        for i in range(0, n, max(1, n // 500)):
            length = math.sqrt(sum(x * x for x in normals.GetTuple3(i)))
            check(abs(length - 1) < 1e-3, f"{path}: normal {i} has length {length}")
    # The speed property, read by struct: within the particles' speeds.
    names = [p[1] for p in props]
    check("speed" in names, f"{path}: no speed property ({names})")
    layout = "<" + "".join({"float": "f", "uchar": "B"}[p[0]] for p in props)
    stride = struct.calcsize(layout)
    k = names.index("speed")
    values = [struct.unpack_from(layout, body, i * stride)[k] for i in range(n)]
    check(min(values) >= min(speeds) - 1e-6 and max(values) <= max(speeds) + 1e-6,
          f"{path}: speeds {min(values)} .. {max(values)} outside the particles' "
          f"{min(speeds)} .. {max(speeds)}")


def particle_speeds(path, dim):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    axes = "xyz"[:dim]
    return [math.sqrt(sum(float(r["v" + a]) ** 2 for a in axes)) for r in rows]


cases = [("dam_break_2d.json", 2, [0, 0], [0.4, 0.25], ["--set", "fluid.spacing=0.004"])]
with tempfile.TemporaryDirectory() as tmp:
    probe = run("dam_break_3d.json", os.path.join(tmp, "probe"), ["--set", "fluid.spacing=0.02"],
                duration="0.001")
    if probe.returncode == 0:
        cases.append(("dam_break_3d.json", 3, [0, 0, 0], [0.4, 0.25, 0.1],
                      ["--set", "fluid.spacing=0.008"]))
    else:
        check("OpenVDB" in probe.stderr, f"3D refused without naming OpenVDB: {probe.stderr}")
        print("3D: this build has no OpenVDB; the 2D case only")
    for scene, dim, lo, hi, extra in cases:
        out = os.path.join(tmp, scene)
        result = run(scene, out, extra)
        check(result.returncode == 0, f"{scene}: exit {result.returncode}: {result.stderr}")
        if result.returncode != 0:
            continue
        for frame in ("frame_00000", "frame_00002"):
            check_ply(os.path.join(out, "surface", frame + ".ply"), lo, hi,
                      particle_speeds(os.path.join(out, "particles", frame + ".csv"), dim))
        check(os.path.exists(os.path.join(out, "surface", "frame_00000.vdb")) == (dim == 3),
              f"{scene}: a .vdb only in 3D")

finish("surface exports read by VTK: ok")
