#!/usr/bin/env python3
"""Reads a run's spheres and bodies frames with VTK's own readers and checks
that a run on MPI ranks (frames in pieces, `.pvtp`, or `.pvtu` for
`vtk_format = "vtu"`) shows every sphere and every body exactly once, with
the values of one process's run.

    check_pvtp.py SERIAL_RUN RANKS_RUN

Runs under ParaView's `pvpython` (or any python with the `vtk` package).
For every frame of SERIAL_RUN/spheres.pvd and bodies.pvd it reads the
serial `.vtp` with vtkXMLPolyDataReader and the ranks' `.pvtp` with
vtkXMLPPolyDataReader (`.vtu` with vtkXMLUnstructuredGridReader, `.pvtu`
with vtkXMLPUnstructuredGridReader), and compares, point by point after ordering by
`body_id` (stable), the points and every point array (exact equality).
With `paraview.simple` at hand, it also opens RANKS_RUN/spheres.pvd as
ParaView does and checks the number of points at the last time.
Prints one line per frame and exits non-zero at the first difference.
"""
import os
import re
import sys

try:
    from vtkmodules.vtkIOXML import (
        vtkXMLPolyDataReader,
        vtkXMLPPolyDataReader,
        vtkXMLPUnstructuredGridReader,
        vtkXMLUnstructuredGridReader,
    )
    from vtkmodules.util.numpy_support import vtk_to_numpy
except ImportError:  # the plain `vtk` package
    from vtk import (
        vtkXMLPolyDataReader,
        vtkXMLPPolyDataReader,
        vtkXMLPUnstructuredGridReader,
        vtkXMLUnstructuredGridReader,
    )
    from vtk.util.numpy_support import vtk_to_numpy
import numpy as np


def frames(run, kind):
    text = open(os.path.join(run, f"{kind}.pvd")).read()
    return re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)


def read(path):
    readers = {
        ".vtp": vtkXMLPolyDataReader,
        ".pvtp": vtkXMLPPolyDataReader,
        ".vtu": vtkXMLUnstructuredGridReader,
        ".pvtu": vtkXMLPUnstructuredGridReader,
    }
    r = readers[os.path.splitext(path)[1]]()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    pd = out.GetPointData()
    arrays = {"Points": vtk_to_numpy(out.GetPoints().GetData())} if out.GetNumberOfPoints() else {}
    for k in range(pd.GetNumberOfArrays()):
        arrays[pd.GetArrayName(k)] = vtk_to_numpy(pd.GetArray(k))
    return out.GetNumberOfPoints(), arrays


def by_body(arrays):
    order = np.argsort(arrays["body_id"], kind="stable")
    return {k: v[order] for k, v in arrays.items()}


def main(serial, ranks):
    checked = 0
    for kind in ("spheres", "bodies"):
        a_list, b_list = frames(serial, kind), frames(ranks, kind)
        if [t for t, _ in a_list] != [t for t, _ in b_list]:
            sys.exit(f"{kind}.pvd: the times differ")
        for (t, fa), (_, fb) in zip(a_list, b_list):
            na, a = read(os.path.join(serial, fa))
            nb, b = read(os.path.join(ranks, fb))
            if na != nb or sorted(a) != sorted(b):
                sys.exit(f"{fb}: {nb} points, arrays {sorted(b)}; serial {fa}: {na}, {sorted(a)}")
            a, b = by_body(a), by_body(b)
            for k in a:
                if not np.array_equal(a[k], b[k]):
                    sys.exit(f"{fb}: array {k} differs from {fa}")
            if kind == "bodies" and len(np.unique(b["body_id"])) != nb:
                sys.exit(f"{fb}: a body is in more than one piece")
            print(f"{fb}: {nb} points, every one once, values as {fa}")
            checked += 1
    try:
        from paraview import simple
    except ImportError:
        simple = None
    if simple is not None:
        src = simple.OpenDataFile(os.path.join(ranks, "spheres.pvd"))
        times = src.TimestepValues
        last = times[-1] if len(times) else 0.0
        src.UpdatePipeline(last)
        n = src.GetDataInformation().GetNumberOfPoints()
        _, fa = frames(serial, "spheres")[-1]
        na, _ = read(os.path.join(serial, fa))
        if n != na:
            sys.exit(f"ParaView reads {n} spheres at t = {last}, one process wrote {na}")
        print(f"ParaView (OpenDataFile spheres.pvd) at t = {last}: {n} spheres, as one process")
    print(f"{checked} frames checked")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
