"""Reads VTK XML files with the `vtk` package and prints their contents as
JSON: for each file, its points, point, cell and field data (numbers as
lists, string arrays as lists of strings). `.pvd` collections are parsed as
XML and each data set they list is read. Exit code 3: `vtk` is missing."""
import json
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError:
    print("vtk not importable")
    sys.exit(3)


def arrays(data):
    out = {}
    for k in range(data.GetNumberOfArrays()):
        a = data.GetAbstractArray(k)
        if isinstance(a, vtk.vtkStringArray):
            out[a.GetName()] = [a.GetValue(i) for i in range(a.GetNumberOfValues())]
        else:
            out[a.GetName()] = vtk_to_numpy(a).tolist()
    return out


def read(path):
    if path.endswith(".pvd"):
        root = ET.parse(path).getroot()
        base = path.rsplit("/", 1)[0]
        sets = [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]
        return {"datasets": [[t, f, read(base + "/" + f)] for t, f in sets]}
    if path.endswith(".vti"):
        r = vtk.vtkXMLImageDataReader()
    else:
        r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    d = r.GetOutput()
    out = {
        "point_data": arrays(d.GetPointData()),
        "cell_data": arrays(d.GetCellData()),
        "field_data": arrays(d.GetFieldData()),
    }
    if path.endswith(".vti"):
        out["dimensions"] = list(d.GetDimensions())
        out["origin"] = list(d.GetOrigin())
        out["spacing"] = list(d.GetSpacing())
    else:
        pts = d.GetPoints()
        out["points"] = vtk_to_numpy(pts.GetData()).tolist() if pts else []
        out["lines"] = d.GetNumberOfLines()
    return out


print(json.dumps({p: read(p) for p in sys.argv[1:]}))
