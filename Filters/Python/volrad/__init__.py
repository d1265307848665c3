"""VolRad: volumetric radiosity for VTK (the classes of VolRad::Filters).

    from volrad import vtkVolumetricRadiosity
"""
# The wrapped module imports the VTK modules it derives from
# (vtkmodules.vtkCommonExecutionModel, ...) itself.
from .VolRadFilters import *  # noqa: F401,F403
