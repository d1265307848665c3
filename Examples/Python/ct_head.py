"""Lights the CT head with volumetric radiosity and renders three pictures.

    PYTHONPATH=build/lib/python3/dist-packages \
        xvfb-run -a /usr/bin/python3 Examples/Python/ct_head.py [OUTDIR] [--size W H]

Reads Data/headsq/quarter.nhdr (the VTKData "headsq" CT, 64x64x93 voxels of
3.2x3.2x1.5 mm), lights it with one white directional light through
vtkVolumetricRadiosity (RGB, the ct material, dense solver) and writes to
OUTDIR (default: out/):

  ct_head_volume.png  volume rendering: colour = albedo colour x baked G,
                      opacity = extinction (emission-absorption, unshaded)
  ct_head_bone.png    bone isosurface coloured by the baked G (no OpenGL lighting)
  ct_head_slice.png   axial slice of G (log scale) with the skin and bone outlines

--size W H sets the pictures' size (default 400 400, the size of the
regression test's baselines), --light DX DY DZ the direction the light
travels, --threads the solver's threads. About 40 s on 2 cores, nearly all of
it the solve.

Rendering is off-screen, but Debian's VTK 9.1 has only the X11 render
window (no EGL, no OSMesa), so it needs an X server: run it under
`xvfb-run -a` (Mesa's llvmpipe renders). ParaView style: VTK classes come
from vtkmodules.vtkXxx, never `import vtk`; no numpy (Debian's python3 has
none), every image operation is a VTK filter.

Lighting on a coarse grid, baked back: the solver's cost grows with the
square of the voxel count (the dense solver handles about 20^3 voxels), so
the volume is solved on a grid 4 times coarser along each axis (voxels
averaged, 16x16x23) and G is interpolated back onto the full-resolution
grid. That is legitimate because radiosity is smooth: multiple scattering
and the soft shadows of a translucent medium vary over many voxels, while
the sharp detail of the picture comes from the full-resolution material
(albedo colour, opacity, isosurface) the baked light is multiplied with.
"""
import math
import os
import time

# Factories of the OpenGL render window and of the volume mapper's display
# helper (without them, vtkRenderWindow() is an abstract object).
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersCore import vtkProbeFilter
from vtkmodules.vtkImagingCore import vtkImageMapToColors, vtkImageShiftScale
from vtkmodules.vtkIOImage import vtkNrrdReader
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkColorTransferFunction,
    vtkPolyDataMapper,
    vtkRenderer,
    vtkVolume,
    vtkVolumeProperty,
)
import lit_grid
# The picture helpers (same folder), shared with frog_labels.py and cloud.py;
# colour_ramp, luminance, with_scalar_bar and write_png, once defined here,
# stay importable from here.
import pictures
from pictures import colour_ramp, luminance, with_scalar_bar, write_png  # noqa: F401
from rgba_volume import rgba_mapper


HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "Data", "headsq", "quarter.nhdr")

# The file's values are 0-3926, not Hounsfield units: air outside the head
# peaks at about 105 (0 outside the scanner's field of view), soft tissue at
# about 1080, bone 1300-2500. They are the usual unsigned CT storage with a
# rescale intercept of -1024: HU = value - 1024 puts air at about -920 (the
# ct material treats everything below -500 as empty), brain and muscle at
# +50, bone at +300 to +1500. So the ct material applies after that shift.
HU_OFFSET = -1024.0

# The "ct" preset of Module/volrad/Material.cxx (HU, mm), repeated here
# because the pictures need its curves too (opacity from the extinction,
# colour from the albedo colour), and passed to the solver explicitly so
# that the solve and the pictures use the same numbers.
EXTINCTION = [[-1000, 0.0], [-500, 0.0], [-100, 0.02], [40, 0.05], [200, 0.2], [700, 2.0],
              [3000, 2.0]]                                            # 1/mm
ALBEDO = [[-500, 0.98], [40, 0.95], [300, 0.8], [1000, 0.7]]
COLOR = [[-100, 1.0, 0.9, 0.7], [40, 1.0, 0.65, 0.55], [300, 1.0, 0.9, 0.85]]  # [HU, r, g, b]
SURFACE_GRADIENT = 100.0                                              # HU/mm

SHRINK = 4                 # solve on a 16x16x23 grid
# Direction the light travels, in the volume's axes. In headsq the face
# looks towards +y, the top of the head is at z = 0 (-z is up; the scan stops
# at mid-forehead, so the top and bottom of the volume are cut faces) and x
# runs across the head. The light comes from the front (+y), from the -x side
# and a little from above: the -x side of the face is lit, the +x side and the
# back of the head are in shadow.
LIGHT_DIRECTION = [0.85, -0.45, 0.25]
IRRADIANCE = 1.0           # W/m^2 on a plane normal to the light
G_WHITE = 1.0              # G shown at full brightness (display exposure)
BONE_HU = 400.0            # isosurface level of bone
SKIN_HU = -400.0           # outline of the skin on the slice
SLICE_RANGE = (1e-3, 1.5)  # G on the slice, log scale
SLICE_K = 30               # axial slice: nose, maxillary sinuses, skull base


def interpolate(points, s, index=1):
    """The piecewise-linear function of `points` (column `index`) at s, constant past the ends."""
    if s <= points[0][0]:
        return points[0][index]
    for a, b in zip(points, points[1:]):
        if s <= b[0]:
            w = (s - a[0]) / (b[0] - a[0])
            return a[index] + w * (b[index] - a[index])
    return points[-1][index]


def parse_args():
    return pictures.parse_args("Light the CT head and render three PNGs.", LIGHT_DIRECTION)


def read_head():
    """The CT in HU (float), origin 0, spacing 3.2 x 3.2 x 1.5 mm."""
    reader = vtkNrrdReader()
    reader.SetFileName(DATA)
    to_hu = vtkImageShiftScale()
    to_hu.SetInputConnection(reader.GetOutputPort())
    to_hu.SetShift(HU_OFFSET)
    to_hu.SetScale(1.0)
    to_hu.SetOutputScalarTypeToFloat()
    return pictures.named_output(to_hu, "HU")


def solve(hu, light, threads):
    """Lights the coarse grid; returns G (3 components) baked onto the full grid."""
    # Average 4x4x4 voxels, each mean at the centre of its voxels.
    centre = lit_grid.average(hu, SHRINK)

    scene = {
        "version": 1,
        "channels": 3,
        "material": {
            "preset": "ct",
            "extinction": EXTINCTION,
            "albedo": ALBEDO,
            "color": COLOR,
            "surface_gradient": SURFACE_GRADIENT,
        },
        "lights": [{"type": "directional", "direction": light, "irradiance": IRRADIANCE}],
        "solver": {"method": "dense"},
    }
    lit = lit_grid.solve(centre, scene, threads, "ct_head")
    return lit_grid.bake(lit, hu)


def render_ready_rgba(hu, G):
    """RGBA unsigned char: RGB = 255 albedo colour x G / G_WHITE, A = (HU + 1024) / 16."""
    # Albedo colour a_c(s) = albedo(s) colour_c(s), sampled every 10 HU.
    albedo_color = vtkColorTransferFunction()
    for s in range(-1100, 1201, 10):
        a = interpolate(ALBEDO, s)
        albedo_color.AddRGBPoint(s, *(a * interpolate(COLOR, s, c) for c in (1, 2, 3)))
    albedo_rgb = vtkImageMapToColors()
    albedo_rgb.SetInputData(hu)
    albedo_rgb.SetLookupTable(albedo_color)
    albedo_rgb.SetOutputFormatToRGB()

    # Display exposure: G_WHITE shows at full brightness, linearly (no tone
    # curve), so that the shadowed side reads as shadow.
    rgb = pictures.lit_colour(albedo_rgb, G, G_WHITE)

    # Alpha: HU in 16-HU steps (-1024 -> 0, 3056 -> 255), looked up by the
    # scalar opacity function below.
    alpha = vtkImageShiftScale()
    alpha.SetInputData(hu)
    alpha.SetShift(-HU_OFFSET)
    alpha.SetScale(1.0 / 16.0)
    alpha.SetOutputScalarTypeToUnsignedChar()
    alpha.ClampOverflowOn()

    return pictures.append_rgba(rgb, alpha)


def head_camera(renderer, azimuth=-20.0, elevation=-10.0, zoom=1.3):
    """A view of the face (which looks towards +y; -z is up), turned by azimuth
    and elevation (degrees)."""
    pictures.orbit_camera(renderer, 1, 1.0, (0, 0, -1), azimuth, elevation, zoom)


def volume_picture(hu, G, size, path):
    """(a) Emission-absorption volume rendering of the baked light: colour =
    albedo colour x G, opacity from the material's extinction."""
    rgba = render_ready_rgba(hu, G)
    # Opacity per mm = 1 - exp(-kappa_t 1 mm), kappa_t the material's
    # extinction: with colour proportional to albedo x G this is the
    # transport the solver modelled (what scatters towards the eye per unit
    # length is sigma_s G / 4 pi = kappa_t a G / 4 pi, attenuated by kappa_t),
    # for the isotropic part of the scattering. Soft tissue is translucent
    # (mean free path 20 mm), so the skull shows through the face.
    opacity = vtkPiecewiseFunction()
    for a in range(0, 256, 2):
        s = 16.0 * a + HU_OFFSET
        opacity.AddPoint(a, 1.0 - math.exp(-interpolate(EXTINCTION, s) * 1.0))
    prop = vtkVolumeProperty()
    prop.IndependentComponentsOff()   # RGB used as is, A through the opacity
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(1.0)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()                   # the light is in the colours already
    # CPU ray caster: the same pixels with any OpenGL (the regression test
    # relies on that), and it takes dependent unsigned char RGBA as is.
    # vtkGPUVolumeRayCastMapper also works here (llvmpipe, OpenGL 4.5).
    # rgba_mapper works around VTK 9.1's space leaping for RGBA (rgba_volume.py).
    mapper = rgba_mapper()
    mapper.SetInputData(rgba)
    mapper.SetSampleDistance(0.5)
    mapper.SetImageSampleDistance(1.0)
    mapper.AutoAdjustSampleDistancesOff()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtkRenderer()
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.AddVolume(volume)
    head_camera(renderer)
    pictures.write_png([renderer], size, path)


def bone_picture(hu, G_lum, size, path):
    """(b) The bone isosurface, its colour the baked G at each point (the
    actor is unlit: ambient 1, diffuse 0, so the colour is the radiosity)."""
    bone = pictures.isosurface(hu, BONE_HU)
    probe = vtkProbeFilter()
    probe.SetInputConnection(bone.GetOutputPort())
    probe.SetSourceData(G_lum)
    probe.Update()
    lo, hi = probe.GetOutput().GetPointData().GetArray("G").GetRange()
    print(f"bone surface at {BONE_HU:g} HU: {probe.GetOutput().GetNumberOfPoints()} points, "
          f"G {lo:.3f} .. {hi:.3f} W/m^2")
    # "bone" colours: black, blue-grey, white.
    lut = pictures.colour_ramp(((0.0, 0.0, 0.0, 0.02), (0.375, 0.32, 0.32, 0.44),
                       (0.75, 0.65, 0.78, 0.78), (1.0, 1.0, 1.0, 1.0)), (0.0, G_WHITE))
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(probe.GetOutputPort())
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("G")
    mapper.SetLookupTable(lut)
    mapper.UseLookupTableScalarRangeOn()
    mapper.ScalarVisibilityOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetAmbient(1.0)
    actor.GetProperty().SetDiffuse(0.0)
    actor.GetProperty().SetSpecular(0.0)
    renderer = vtkRenderer()
    renderer.SetBackground(*pictures.BACKGROUND)
    renderer.AddActor(actor)
    head_camera(renderer)
    pictures.write_png(pictures.with_scalar_bar(renderer, lut, "G (W/m2)", pictures.BACKGROUND),
                       size, path)


def slice_picture(hu, G_lum, size, path):
    """(c) An axial slice of G through the nose and the skull base (log
    colour scale), with the skin and bone outlines, seen from below (the
    radiological convention: the face at the top, the head's -x side, where
    the light comes from, on the left)."""
    k = SLICE_K
    z = hu.GetOrigin()[2] + k * hu.GetSpacing()[2]
    renderer, lut = pictures.slice_scene(G_lum, 2, k, SLICE_RANGE)
    # Outlines: the skin and bone isosurfaces cut by the slice plane, moved
    # 1 mm towards the camera (at +z) so that they are drawn over the image.
    for level, color in ((SKIN_HU, (0.55, 0.8, 1.0)), (BONE_HU, (1.0, 1.0, 1.0))):
        renderer.AddActor(pictures.outline(pictures.isosurface(hu, level), 2, z, 1.0, color))
    # The whole slice in the scene's viewport.
    bounds = hu.GetBounds()
    pictures.slice_camera(renderer, 2, 1.0, (0, 1, 0), bounds[3] - bounds[2], bounds[1] - bounds[0],
                          size)
    pictures.write_slice_png(renderer, lut, (0.001, 0.01, 0.1, 1.0), size, path)


def main():
    args = parse_args()
    start = time.time()
    hu = read_head()
    pictures.print_read(DATA, hu, "HU")
    G = solve(hu, args.light, args.threads)
    G_lum = pictures.baked_luminance(G, start)
    volume_picture(hu, G, args.size, os.path.join(args.outdir, "ct_head_volume.png"))
    bone_picture(hu, G_lum, args.size, os.path.join(args.outdir, "ct_head_bone.png"))
    slice_picture(hu, G_lum, args.size, os.path.join(args.outdir, "ct_head_slice.png"))
    print(f"done in {time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
