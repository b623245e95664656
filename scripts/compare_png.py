#!/usr/bin/python3
"""Prints how two PNG images of one size differ: the mean absolute difference of their
8-bit values and the share of values more than 16 levels apart (markdown).

  compare_png.py A.png B.png
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    if image.GetNumberOfPoints() == 0:
        sys.exit("cannot read %s" % path)
    return image.GetDimensions(), vtk_to_numpy(image.GetPointData().GetScalars()).astype(float)


def main(a, b):
    (dims_a, va), (dims_b, vb) = pixels(a), pixels(b)
    if dims_a != dims_b or va.shape != vb.shape:
        sys.exit("%s and %s differ in size" % (a, b))
    difference = np.abs(va - vb)
    print("%s against %s: mean |difference| %.3f of 255, %.3f%% of the values more than 16 "
          "apart" % (b, a, difference.mean(), 100.0 * (difference > 16).mean()))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
