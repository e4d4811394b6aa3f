#!/usr/bin/env python3
"""Reads sphclip's particle exports with VTK's own readers (Debian
python3-vtk9), an implementation independent of sphclip's writer, and checks
them against the CSV export of the same run: same particles, ids, positions,
velocities, densities and pressures, and the .pvd's time steps equal to the
CSV's time column. Binary (--export vtk) and ASCII (--export vtk-ascii)
files both. Exits 77 (ctest's "skipped") when VTK's Python module is absent.

usage: check_with_vtk.py PATH/TO/sphclip SOURCE_DIR"""
import csv
import math
import os
import tempfile
import xml.etree.ElementTree as ET

from vtk_checks import check, finish, vtk
import vtk_checks


def run(scene, out, exports, extra):
    args = [a for e in exports for a in ("--export", e)]
    vtk_checks.run(scene, out, args + extra, check=True)


def read_vtp(path):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    check(reader.GetErrorCode() == 0, f"{path}: VTK reports error {reader.GetErrorCode()}")
    data = reader.GetOutput()
    n = data.GetNumberOfPoints()
    points = [data.GetPoint(i) for i in range(n)]

    def values(name):
        array = data.GetPointData().GetArray(name)
        check(array is not None, f"{path}: no point array {name}")
        if array.GetNumberOfComponents() == 1:
            return [array.GetValue(i) for i in range(n)]
        return [array.GetTuple(i) for i in range(n)]
    arrays = {name: values(name) for name in ("velocity", "density", "pressure", "id")}
    return data, points, arrays


def close(a, b):
    return math.isclose(float(a), float(b), rel_tol=2e-8, abs_tol=1e-12)


with tempfile.TemporaryDirectory() as tmp:
    for scene, dim, extra in (("dam_break_2d.json", 2, []),
                              ("dam_break_3d.json", 3, ["--set", "fluid.spacing=0.008"])):
        binary = os.path.join(tmp, f"binary{dim}")
        ascii_ = os.path.join(tmp, f"ascii{dim}")
        run(scene, binary, ["csv", "vtk"], extra)
        run(scene, ascii_, ["vtk-ascii"], extra)
        pvd = ET.parse(os.path.join(binary, "particles.pvd")).getroot()
        datasets = pvd.find("Collection").findall("DataSet")
        check(len(datasets) == 3, f"{scene}: {len(datasets)} time steps in particles.pvd, not 3")
        for k, dataset in enumerate(datasets):
            name = dataset.get("file")
            rows = list(csv.DictReader(open(os.path.join(binary, "particles",
                                                          f"frame_{k:05d}.csv"))))
            check(all(close(r["time"], dataset.get("timestep")) for r in rows),
                  f"{name}: CSV time differs from the .pvd's time step")
            for folder, label in ((binary, "binary"), (ascii_, "ascii")):
                path = os.path.join(folder, name)
                text = open(path, "rb").read()
                check((b"vtkZLibDataCompressor" in text) == (label == "binary"),
                      f"{path}: compression as expected of {label}")
                data, points, arrays = read_vtp(path)
                check(data.GetNumberOfPoints() == len(rows),
                      f"{path}: {data.GetNumberOfPoints()} points, the CSV {len(rows)}")
                check(data.GetNumberOfVerts() == len(rows), f"{path}: one vertex cell per point")
                axes = "xyz"[:dim]
                for i, row in enumerate(rows):
                    ok = int(arrays["id"][i]) == int(row["id"])
                    ok = ok and all(close(points[i][a], row[axes[a]]) for a in range(dim))
                    ok = ok and all(close(arrays["velocity"][i][a], row["v" + axes[a]])
                                    for a in range(dim))
                    ok = ok and close(arrays["density"][i], row["density"])
                    ok = ok and close(arrays["pressure"][i], row["pressure"])
                    if dim == 2:
                        ok = ok and points[i][2] == 0 and arrays["velocity"][i][2] == 0
                    if not ok:
                        check(False, f"{path}: particle row {i} differs from the CSV: {row}")
                        break
        print(f"{scene}: {len(datasets)} frames of {len(rows)} particles read by VTK "
              f"{vtk.vtkVersion.GetVTKVersion()}, binary and ascii, equal to the CSV")

finish("all VTK checks passed")
