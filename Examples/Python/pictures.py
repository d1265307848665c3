"""Picture making shared by the CT head, frog and cloud examples: the
command line, the render-ready RGBA, the cameras, the slice of G with its
outlines, the colour ramps, the scalar bar and the window grab.

Every picture is rendered off-screen into a PNG of the size the command line
asks for; the regression-image tests compare them with Testing/Baseline, so
what is here must give the same pixels on every run.
"""
import argparse
import math
import os
import time

# Factories of the OpenGL render window (without them, vtkRenderWindow() is
# an abstract object).
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkmodules.vtkCommonCore import VTK_FLOAT, vtkDoubleArray, vtkLookupTable
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPlane
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkCutter, vtkFlyingEdges3D
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkImagingColor import vtkImageLuminance
from vtkmodules.vtkImagingCore import vtkImageAppendComponents, vtkImageCast, vtkImageShiftScale
from vtkmodules.vtkImagingMath import vtkImageMathematics
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkColorTransferFunction,
    vtkImageSlice,
    vtkImageSliceMapper,
    vtkPolyDataMapper,
    vtkRenderer,
    vtkRenderWindow,
    vtkWindowToImageFilter,
)

BACKGROUND = (0.1, 0.1, 0.12)      # behind the isosurfaces and the slices
OUTLINE_COLOR = (0.55, 0.8, 1.0)   # the outlines on the slices
# inferno-like, for G on the slices: black, purple, orange, pale yellow.
INFERNO = ((0.0, 0.0, 0.0, 0.02), (0.25, 0.26, 0.04, 0.41), (0.5, 0.73, 0.21, 0.33),
           (0.75, 0.98, 0.55, 0.04), (1.0, 0.99, 1.0, 0.64))


def parse_args(description, light, light_help="direction the light travels"):
    """The examples' command line: OUTDIR (created), --size W H, --light DX DY DZ, --threads."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("outdir", nargs="?", default="out", help="folder for the PNGs (default out/)")
    parser.add_argument("--size", nargs=2, type=int, default=[400, 400], metavar=("W", "H"),
                        help="image size in pixels (default 400 400)")
    parser.add_argument("--light", nargs=3, type=float, default=light,
                        metavar=("DX", "DY", "DZ"), help=light_help)
    parser.add_argument("--threads", type=int, default=0, help="solver threads (0: all cores)")
    args = parser.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    return args


def named_output(algorithm, name):
    """The algorithm's output, brought up to date, its scalars named `name`."""
    algorithm.Update()
    out = algorithm.GetOutput()
    out.GetPointData().GetScalars().SetName(name)
    return out


def luminance(G):
    """One component of G for colour maps: 0.30 R + 0.59 G + 0.11 B (vtkImageLuminance)."""
    lum = vtkImageLuminance()
    lum.SetInputData(G)
    return named_output(lum, "G")


def print_read(path, image, what):
    """Prints the grid and the scalar range (`what`) of the image read from `path`."""
    lo, hi = image.GetScalarRange()
    print(f"read {path}: {image.GetDimensions()} voxels, spacing {image.GetSpacing()} mm, "
          f"{what} {lo:.0f} .. {hi:.0f}")


def baked_luminance(G, start):
    """luminance(G), its range and the time since `start` printed."""
    G_lum = luminance(G)
    print(f"baked G onto {G.GetDimensions()}: {G_lum.GetScalarRange()[0]:.3f} .. "
          f"{G_lum.GetScalarRange()[1]:.3f} W/m^2 ({time.time() - start:.1f} s)")
    return G_lum


def lit_colour(albedo_rgb, G, g_white):
    """Unsigned char RGB = albedo colour x G / g_white, the albedo colour
    (`albedo_rgb`, an algorithm) in 0-255 already: g_white shows at full
    brightness, linearly (no tone curve), so that shadow reads as shadow."""
    albedo_float = vtkImageCast()
    albedo_float.SetInputConnection(albedo_rgb.GetOutputPort())
    albedo_float.SetOutputScalarTypeToFloat()
    exposure = vtkImageMathematics()
    exposure.SetInputData(G)
    exposure.SetOperationToMultiplyByK()
    exposure.SetConstantK(1.0 / g_white)
    product = vtkImageMathematics()   # component by component
    product.SetOperationToMultiply()
    product.SetInputConnection(0, albedo_float.GetOutputPort())
    product.SetInputConnection(1, exposure.GetOutputPort())
    rgb = vtkImageShiftScale()
    rgb.SetInputConnection(product.GetOutputPort())
    rgb.SetOutputScalarTypeToUnsignedChar()
    rgb.ClampOverflowOn()
    return rgb


def scattering_rgba(density, G, brightness, kappa_per_density, opacity_unit):
    """RGBA unsigned char of a white scattering medium (a cloud, smoke):
    RGB = 255 x brightness x G (brightness: albedo over the G shown at full
    white), A = 255 x the opacity of `opacity_unit` of length, the
    extinction being kappa_per_density x density."""
    rgb = vtkImageShiftScale()
    rgb.SetInputData(G)
    rgb.SetScale(255.0 * brightness)
    rgb.SetOutputScalarTypeToUnsignedChar()
    rgb.ClampOverflowOn()

    # 1 - exp(-kappa opacity_unit), kappa = kappa_per_density x density.
    alpha = vtkImageData()
    alpha.CopyStructure(density)
    alpha.AllocateScalars(VTK_FLOAT, 1)
    rho = density.GetPointData().GetScalars()
    values = alpha.GetPointData().GetScalars()
    for n in range(rho.GetNumberOfTuples()):
        values.SetValue(n, 255.0 * (1.0 - math.exp(-kappa_per_density * rho.GetValue(n)
                                                    * opacity_unit)))
    alpha_byte = vtkImageShiftScale()
    alpha_byte.SetInputData(alpha)
    alpha_byte.SetOutputScalarTypeToUnsignedChar()
    alpha_byte.ClampOverflowOn()

    return append_rgba(rgb, alpha_byte)


def append_rgba(rgb, alpha):
    """The RGBA image of two algorithms' outputs, RGB and A."""
    rgba = vtkImageAppendComponents()
    rgba.AddInputConnection(rgb.GetOutputPort())
    rgba.AddInputConnection(alpha.GetOutputPort())
    rgba.Update()
    return rgba.GetOutput()


def _along(axis, value):
    """A 3-vector, `value` along `axis` (0, 1, 2), 0 elsewhere."""
    v = [0.0, 0.0, 0.0]
    v[axis] = value
    return v


def orbit_camera(renderer, axis, sign, view_up, azimuth=0.0, elevation=0.0, zoom=1.0):
    """A perspective view along `axis` from its `sign` side (+1, -1), turned
    by azimuth and elevation (degrees), zoomed."""
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    position = list(camera.GetFocalPoint())
    position[axis] += sign * camera.GetDistance()
    camera.SetPosition(*position)
    camera.SetViewUp(*view_up)
    if azimuth:
        camera.Azimuth(azimuth)
    if elevation:
        camera.Elevation(elevation)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera()
    camera.Zoom(zoom)


def slice_camera(renderer, axis, sign, view_up, height, width, size, at=None):
    """A parallel view along `axis` from its `sign` side, centred on the
    plane `axis` = `at` (if given), fitting a slice `height` x `width`
    (along the view up and across) into the scene's viewport (80% of the
    window's width)."""
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    position = list(camera.GetFocalPoint())
    if at is not None:
        position[axis] = at
        camera.SetFocalPoint(*position)
    position[axis] += sign * camera.GetDistance()
    camera.SetPosition(*position)
    camera.SetViewUp(*view_up)
    camera.ParallelProjectionOn()
    renderer.ResetCamera()
    aspect = 0.8 * size[0] / size[1]
    camera.SetParallelScale(0.51 * max(height, width / aspect))


def isosurface(image, level):
    """The surface where `image` takes `level` (no normals)."""
    surface = vtkFlyingEdges3D()
    surface.SetInputData(image)
    surface.SetValue(0, level)
    surface.ComputeNormalsOff()
    return surface


def outline(surface, axis, at, shift, color=OUTLINE_COLOR):
    """An unlit line actor: `surface` (an algorithm giving poly data) cut by
    the plane `axis` = `at`, moved by `shift` along `axis` (towards the
    camera, so that it is drawn over the slice)."""
    plane = vtkPlane()
    plane.SetOrigin(*_along(axis, at))
    plane.SetNormal(*_along(axis, 1.0))
    cut = vtkCutter()
    cut.SetInputConnection(surface.GetOutputPort())
    cut.SetCutFunction(plane)
    toward_camera = vtkTransform()
    toward_camera.Translate(*_along(axis, shift))
    move = vtkTransformPolyDataFilter()
    move.SetInputConnection(cut.GetOutputPort())
    move.SetTransform(toward_camera)
    line_mapper = vtkPolyDataMapper()
    line_mapper.SetInputConnection(move.GetOutputPort())
    line_mapper.ScalarVisibilityOff()
    lines = vtkActor()
    lines.SetMapper(line_mapper)
    lines.GetProperty().SetColor(*color)
    lines.GetProperty().SetLineWidth(1.0)
    lines.GetProperty().LightingOff()
    return lines


def slice_scene(G_lum, axis, index, table_range):
    """A renderer showing slice `index` normal to `axis` of G (log colour
    scale over table_range, INFERNO), and its lookup table."""
    lut = colour_ramp(INFERNO, table_range, log=True)
    mapper = vtkImageSliceMapper()
    mapper.SetInputData(G_lum)
    mapper.SetOrientation(axis)
    mapper.SetSliceNumber(index)
    image = vtkImageSlice()
    image.SetMapper(mapper)
    image.GetProperty().SetLookupTable(lut)
    image.GetProperty().UseLookupTableScalarRangeOn()
    image.GetProperty().SetInterpolationTypeToLinear()
    renderer = vtkRenderer()
    renderer.SetBackground(*BACKGROUND)
    renderer.AddViewProp(image)
    return renderer, lut


def write_slice_png(renderer, lut, ticks, size, path):
    """The slice's scene with a G scalar bar labelled at `ticks`, into `path`."""
    labels = vtkDoubleArray()
    for v in ticks:
        labels.InsertNextValue(v)
    write_png(with_scalar_bar(renderer, lut, "G (W/m2)", BACKGROUND, labels), size, path)


def write_png(renderers, size, path):
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*size)
    window.SetMultiSamples(0)  # the same pixels on every run
    for renderer in renderers:
        window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(path)
    writer.Write()
    window.Finalize()
    print(f"wrote {path}")


def colour_ramp(points, table_range, log=False):
    """A 256-entry lookup table interpolating (x in [0, 1], r, g, b) points."""
    ramp = vtkColorTransferFunction()
    for x, r, g, b in points:
        ramp.AddRGBPoint(x, r, g, b)
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(256)
    for i in range(256):
        lut.SetTableValue(i, *ramp.GetColor(i / 255.0), 1.0)
    if log:
        lut.SetScaleToLog10()
    lut.SetTableRange(*table_range)
    lut.Build()
    return lut


def with_scalar_bar(scene, lut, title, background, labels=None):
    """The scene on the left 80% of the window, a scalar bar on the right."""
    scene.SetViewport(0.0, 0.0, 0.8, 1.0)
    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(title)
    bar.SetNumberOfLabels(5)
    bar.SetLabelFormat("%.3g")
    bar.SetPosition(0.05, 0.08)
    bar.SetWidth(0.9)
    bar.SetHeight(0.84)
    bar.SetBarRatio(0.3)
    if labels is not None:
        bar.SetUseCustomLabels(True)
        bar.SetCustomLabels(labels)
    bar.UnconstrainedFontSizeOn()
    bar.GetTitleTextProperty().SetFontSize(13)
    bar.GetLabelTextProperty().SetFontSize(12)
    side = vtkRenderer()
    side.SetViewport(0.8, 0.0, 1.0, 1.0)
    side.SetBackground(*background)
    side.AddActor2D(bar)
    return [scene, side]
