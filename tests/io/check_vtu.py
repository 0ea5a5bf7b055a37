#!/usr/bin/python3
"""Reads a .vtu or .vtp with VTK's XML readers (the readers ParaView uses), or every file a
ParaView collection (.pvd) lists, and prints what it found as JSON: points, cells, cell types,
and every point/cell array with its components and values (NaN as null: JSON has no NaN).
Used by hotmesh's tests to check our VTU files against an independent implementation."""
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy


def arrays(data):
    out = {}
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        out[a.GetName()] = {
            "components": a.GetNumberOfComponents(),
            "type": a.GetDataTypeAsString(),
            "values": [None if isinstance(v, float) and math.isnan(v) else v
                       for v in vtk_to_numpy(a).ravel().tolist()],
        }
    return out


def cells_of(data):
    cells = []
    for c in range(data.GetNumberOfCells()):
        ids = data.GetCell(c).GetPointIds()
        cells.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    return cells


def read(path):
    """What VTK's reader of the file's kind finds in it, as a dict."""
    if path.endswith(".vtp"):
        reader = vtkXMLPolyDataReader()
    else:
        reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        return {"error": reader.GetErrorCode()}
    data = reader.GetOutput()
    points = data.GetPoints()
    return {
        "points": vtk_to_numpy(points.GetData()).ravel().tolist() if points else [],
        "cell_types": [data.GetCellType(c) for c in range(data.GetNumberOfCells())],
        "cells": cells_of(data),
        "point_data": arrays(data.GetPointData()),
        "cell_data": arrays(data.GetCellData()),
    }


def read_collection(path):
    """A ParaView .pvd: every data set it lists, with its time, read by VTK."""
    folder = os.path.dirname(path)
    steps = []
    for dataset in ET.parse(path).getroot().iter("DataSet"):
        step = read(os.path.join(folder, dataset.get("file")))
        step["time"] = float(dataset.get("timestep"))
        step["file"] = dataset.get("file")
        steps.append(step)
    return {"steps": steps}


def main(path):
    seen = read_collection(path) if path.endswith(".pvd") else read(path)
    print(json.dumps(seen))
    return 1 if "error" in seen else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
