"""Volume rendering of render-ready RGBA (colour and opacity per voxel) with
VTK 9.1's CPU ray caster, shared by the frog and cloud examples.

vtkFixedPointVolumeRayCastMapper with IndependentComponentsOff takes
unsigned char RGBA as is (RGB the colour, A through the scalar opacity
function) and gives the same pixels with any OpenGL, which the
regression-image tests rely on. But in VTK 9.1 its space-leaping filter
(vtkVolumeRayCastSpaceLeapingImageFilter, a threaded image algorithm) reads
the wrong voxels for dependent components in every piece of the volume but
the first: it offsets the piece's start by one component per voxel instead
of four. The min-max blocks of those pieces then describe other voxels,
and the caster skips blocks that hold matter: whole parts of a volume
(the frog's legs, for instance) vanish, and which ones depends on how the
volume is split (Debian's VTK splits it into many SMP pieces by default).
One piece avoids it: the mapper below is built while imaging filters
default to one thread without SMP, which its space-leaping filter keeps;
the ray casting itself still uses every core.
"""
from vtkmodules.vtkCommonCore import vtkMultiThreader
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkCommonExecutionModel import vtkThreadedImageAlgorithm
from vtkmodules.vtkRenderingCore import vtkVolume, vtkVolumeProperty
from vtkmodules.vtkRenderingVolume import vtkFixedPointVolumeRayCastMapper


def rgba_mapper():
    """A vtkFixedPointVolumeRayCastMapper whose space leaping runs as one piece."""
    smp = vtkThreadedImageAlgorithm.GetGlobalDefaultEnableSMP()
    threads = vtkMultiThreader.GetGlobalDefaultNumberOfThreads()
    vtkThreadedImageAlgorithm.SetGlobalDefaultEnableSMP(False)
    vtkMultiThreader.SetGlobalDefaultNumberOfThreads(1)
    try:
        mapper = vtkFixedPointVolumeRayCastMapper()
    finally:
        vtkThreadedImageAlgorithm.SetGlobalDefaultEnableSMP(smp)
        vtkMultiThreader.SetGlobalDefaultNumberOfThreads(threads)
    mapper.SetNumberOfThreads(threads)   # the rays: every core
    return mapper


def rgba_volume(rgba, opacity_unit, sample_distance):
    """A vtkVolume of unsigned char RGBA: RGB the colour as is, A / 255 the
    opacity of `opacity_unit` (length units), linear interpolation, no
    shading of its own (the light is in the colours)."""
    opacity = vtkPiecewiseFunction()    # identity: A is the opacity already
    opacity.AddPoint(0, 0.0)
    opacity.AddPoint(255, 1.0)
    prop = vtkVolumeProperty()
    prop.IndependentComponentsOff()     # RGB used as is, A through the opacity
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(opacity_unit)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    mapper = rgba_mapper()
    mapper.SetInputData(rgba)
    mapper.SetSampleDistance(sample_distance)
    mapper.SetImageSampleDistance(1.0)
    mapper.AutoAdjustSampleDistancesOff()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    return volume
