"""Solving on a coarse grid and baking the light onto a finer one, shared by
the CT head, frog and cloud examples.

Multiply scattered light is smooth, so a coarse grid carries it; the detail
of the pictures comes from the full-resolution material it multiplies.
"""
import json
import sys

from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkImagingCore import vtkImageChangeInformation, vtkImageReslice, vtkImageShrink3D

from volrad import vtkVolumetricRadiosity


def average(image, factor):
    """`image` averaged over blocks of factor^3 voxels (an algorithm, not
    updated). vtkImageShrink3D keeps the origin, but the mean of fine voxels
    f i .. f i + f - 1 belongs at their centre, (f - 1) / 2 fine voxels
    further: the origin moves there."""
    shrink = vtkImageShrink3D()
    shrink.SetInputData(image)
    shrink.SetShrinkFactors(factor, factor, factor)
    shrink.AveragingOn()
    centre = vtkImageChangeInformation()
    centre.SetInputConnection(shrink.GetOutputPort())
    centre.SetOriginTranslation([(factor - 1) / 2.0 * s for s in image.GetSpacing()])
    return centre


def solve(source, scene, threads, who):
    """vtkVolumetricRadiosity on `source` (image data, or an algorithm whose
    output it takes) with the scene (a dict, the scene file's JSON); prints
    the solve's figures; exits with a message when the solve fails."""
    radiosity = vtkVolumetricRadiosity()
    if hasattr(source, "GetOutputPort"):
        radiosity.SetInputConnection(source.GetOutputPort())
    else:
        radiosity.SetInputData(source)
    radiosity.SetSceneJSON(json.dumps(scene))
    radiosity.SetNumberOfThreads(threads)
    radiosity.Update()
    lit = radiosity.GetOutput()
    if lit.GetPointData().GetArray("IncidentRadiation") is None:
        sys.exit(f"{who}: the solve failed (see the VTK error above)")
    fd = lit.GetFieldData()
    residual = fd.GetArray("EnergyBalanceResidual").GetComponent(0, 0)
    print(f"solved {lit.GetDimensions()} voxels: {fd.GetAbstractArray('SolverMethod').GetValue(0)}, "
          f"{fd.GetArray('SolveSeconds').GetValue(0):.1f} s, energy balance residual {residual:.2g}")
    return lit


def bake(lit, fine):
    """G of `lit` interpolated (trilinear) onto `fine`'s grid; mirror padding
    covers the part of a coarse voxel at the borders its point does not reach."""
    coarse = vtkImageData()
    coarse.CopyStructure(lit)
    coarse.GetPointData().SetScalars(lit.GetPointData().GetArray("IncidentRadiation"))
    reslice = vtkImageReslice()
    reslice.SetInputData(coarse)
    reslice.SetInformationInput(fine)
    reslice.SetInterpolationModeToLinear()
    reslice.MirrorOn()
    reslice.Update()
    G = reslice.GetOutput()
    G.GetPointData().GetScalars().SetName("IncidentRadiation")
    return G
