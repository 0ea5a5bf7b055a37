#!/usr/bin/python3
"""Reads a .vtu with VTK's XML reader (the reader ParaView uses) and prints what it found as
JSON: counts, cell types, and every point/cell array with its components and values.
Used by hotmesh's tests to check our VTU files against an independent implementation."""
import json
import sys

from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy


def arrays(data):
    out = {}
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        out[a.GetName()] = {
            "components": a.GetNumberOfComponents(),
            "type": a.GetDataTypeAsString(),
            "values": vtk_to_numpy(a).ravel().tolist(),
        }
    return out


def main(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        print(json.dumps({"error": reader.GetErrorCode()}))
        return 1
    grid = reader.GetOutput()
    cells = []
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        cells.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    print(json.dumps({
        "points": vtk_to_numpy(grid.GetPoints().GetData()).ravel().tolist(),
        "cell_types": [grid.GetCellType(c) for c in range(grid.GetNumberOfCells())],
        "cells": cells,
        "point_data": arrays(grid.GetPointData()),
        "cell_data": arrays(grid.GetCellData()),
    }))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
