#!/usr/bin/env python3
"""Makes neghip16.vti, the small volume the dense solver's examples use.

Source: ../shared/data/neghip/neghip.slc (VolVis "neghip", the electron
probability density of a high-potential iron protein, 66^3, from VTKData;
see VTKData-Copyright.txt). It is resampled to 16^3 over a unit cube and
mapped to optical coefficients of a glowing cloud:
  density  = value / 255
  kappa_a  = 2 * density    [1/unit length]
  sigma_i  = 12 * density   [1/unit length]  (albedo 0.86)
  E_I      = 1 where density > 0.5, else 0  [W/m^2]
Run: /usr/bin/python3 Data/make_neghip16.py ../shared/data/neghip/neghip.slc Data/neghip16.vti
"""
import sys

from vtkmodules.vtkIOImage import vtkSLCReader
from vtkmodules.vtkImagingCore import vtkImageResize
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
from vtkmodules.vtkCommonCore import vtkFloatArray

src, dst = sys.argv[1], sys.argv[2]
reader = vtkSLCReader()
reader.SetFileName(src)
resize = vtkImageResize()
resize.SetInputConnection(reader.GetOutputPort())
resize.SetOutputDimensions(16, 16, 16)
resize.Update()
image = resize.GetOutput()
image.SetSpacing(1 / 16, 1 / 16, 1 / 16)
image.SetOrigin(0.5 / 16, 0.5 / 16, 0.5 / 16)
values = image.GetPointData().GetScalars()
n = image.GetNumberOfPoints()
arrays = {name: vtkFloatArray() for name in ("density", "kappa_a", "sigma_i", "E_I")}
for name, a in arrays.items():
    a.SetName(name)
    a.SetNumberOfTuples(n)
for i in range(n):
    d = values.GetTuple1(i) / 255.0
    arrays["density"].SetValue(i, d)
    arrays["kappa_a"].SetValue(i, 2.0 * d)
    arrays["sigma_i"].SetValue(i, 12.0 * d)
    arrays["E_I"].SetValue(i, 1.0 if d > 0.5 else 0.0)
pd = image.GetPointData()
pd.RemoveArray(values.GetName())
for a in arrays.values():
    pd.AddArray(a)
pd.SetActiveScalars("density")
writer = vtkXMLImageDataWriter()
writer.SetFileName(dst)
writer.SetInputData(image)
writer.Write()
print(f"wrote {dst}: {image.GetDimensions()}, density range {arrays['density'].GetRange()}")
