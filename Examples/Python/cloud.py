"""Lights a procedural cloud with the sun and a blue sky and renders two pictures.

    PYTHONPATH=build/lib/python3/dist-packages \
        xvfb-run -a /usr/bin/python3 Examples/Python/cloud.py [OUTDIR] [--size W H]

Makes a cumulus-like density field (smooth noise inside a flattened
ellipsoid, no data file), maps it with the "cloud" material preset
(extinction proportional to density, 0.5 optical depth per voxel at the
densest, albedo 0.99, white, isotropic), lights it through
vtkVolumetricRadiosity with a white sun (a directional light) and a blue sky
(radiance entering through the open top face), in RGB, and writes to OUTDIR
(default: out/):

  cloud_volume.png  volume rendering: colour = albedo x baked G, opacity =
                    extinction, over a sky-coloured background
  cloud_slice.png   G on a vertical slice through the cloud (log scale),
                    the cloud's outline drawn

--size W H sets the pictures' size (default 400 400, the size of the
regression test's baselines), --light DX DY DZ the direction the sunlight
travels, --threads the solver's threads. About 10 s on 2 cores, most of it
the solve.

The domain is a 3 km cube, z up. The density is computed on a 60^3 grid
(50 m voxels) for the pictures and averaged 3x3x3 onto the 20^3 grid the
dense solver lights (150 m voxels, 0.5 optical depth each at the densest:
a mean free path of 300 m; optical depth 5.6 across the cloud's middle, 3.8
from top to bottom at most); G is then
interpolated back onto the 60^3 grid, whose finer density gives the
pictures their detail, as in ct_head.py. The material is the preset's on
the solve's grid: the pictures use the same extinction per km (a voxel of
the picture's grid, a third of the size, has a third of the optical depth).
"""
import argparse
import math
import os
import time

# Factories of the OpenGL render window and of the volume mapper's display
# helper (without them, vtkRenderWindow() is an abstract object).
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
from vtkmodules.vtkCommonCore import VTK_FLOAT, vtkDoubleArray, vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPlane
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkCutter, vtkFlyingEdges3D
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkImagingCore import (
    vtkImageAppendComponents,
    vtkImageChangeInformation,
    vtkImageShiftScale,
    vtkImageShrink3D,
)
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkImageSlice,
    vtkImageSliceMapper,
    vtkPolyDataMapper,
    vtkRenderer,
)


# The picture helpers of the CT head example (same folder) and the RGBA
# volume (see rgba_volume.py for the VTK 9.1 bug it avoids).
from ct_head import colour_ramp, luminance, with_scalar_bar, write_png
import lit_grid
from rgba_volume import rgba_volume

FINE = 60                  # the pictures' grid, FINE^3 voxels
SHRINK = 3                 # solve on (FINE / SHRINK)^3 = 20^3 voxels
SIZE_KM = 3.0              # the domain's edge
# The preset's extinction: 0.5 optical depth per solve-grid voxel at the
# densest (the largest density of the solve's grid: "relative").
OPTICAL_DEPTH_PER_VOXEL = 0.5
ALBEDO = 0.99
# Direction the sunlight travels: from the -x side (the left of the
# pictures), 50 degrees above the horizon, a little from -y.
LIGHT_DIRECTION = [0.6, 0.25, -0.76]
SUN_IRRADIANCE = 1.0                    # W/m^2 on a plane normal to the sun, white
SKY_RADIANCE = [0.02, 0.04, 0.08]       # W/(m^2 sr), entering through the top
G_WHITE = 2.0              # G shown at full brightness (display exposure)
OPACITY_UNIT = 0.1         # km: the volume's alpha is the opacity of 100 m
OUTLINE = 0.15             # the cloud's outline on the slice, fraction of the peak density
SLICE_RANGE = (0.05, 2.5)  # G on the slice, log scale


def parse_args():
    parser = argparse.ArgumentParser(description="Light a procedural cloud and render two PNGs.")
    parser.add_argument("outdir", nargs="?", default="out", help="folder for the PNGs (default out/)")
    parser.add_argument("--size", nargs=2, type=int, default=[400, 400], metavar=("W", "H"),
                        help="image size in pixels (default 400 400)")
    parser.add_argument("--light", nargs=3, type=float, default=LIGHT_DIRECTION,
                        metavar=("DX", "DY", "DZ"), help="direction the sunlight travels")
    parser.add_argument("--threads", type=int, default=0, help="solver threads (0: all cores)")
    return parser.parse_args()


def cloud_density(u, v, w):
    """Density in [0, 1] at (u, v, w) in the unit cube (w up): smooth noise
    (a few sine products, wavelengths 0.3-2 km) inside an ellipsoid
    2.5 x 2.1 x 1.6 km, with a flat base at 0.8 km."""
    du, dv, dw = (u - 0.5) / 0.42, (v - 0.5) / 0.35, (w - 0.5) / 0.27
    envelope = 1.0 - (du * du + dv * dv + dw * dw)
    noise = (math.sin(11.0 * u + 1.0) * math.sin(13.0 * v + 2.0) * math.sin(9.0 * w)
             + 0.5 * math.sin(23.0 * u + 17.0 * v) * math.cos(19.0 * w + 3.0)
             + 0.4 * math.sin(41.0 * u - 7.0) * math.sin(37.0 * v + 29.0 * w + 1.0)
             + 0.25 * math.sin(61.0 * w + 31.0 * u) * math.sin(53.0 * v - 3.0))
    base = min(1.0, max(0.0, (w - 0.27) / 0.04))      # flat bottom
    return max(0.0, min(1.0, 2.0 * (0.7 * envelope + 0.3 * noise) - 0.2)) * base


def make_cloud():
    """The density on the FINE^3 grid (km, origin at the first voxel centre)."""
    h = SIZE_KM / FINE
    image = vtkImageData()
    image.SetDimensions(FINE, FINE, FINE)
    image.SetSpacing(h, h, h)
    image.SetOrigin(h / 2, h / 2, h / 2)
    density = vtkFloatArray()
    density.SetName("density")
    density.SetNumberOfTuples(FINE ** 3)
    index = 0
    for k in range(FINE):
        w = (k + 0.5) / FINE
        for j in range(FINE):
            v = (j + 0.5) / FINE
            for i in range(FINE):
                density.SetValue(index, cloud_density((i + 0.5) / FINE, v, w))
                index += 1
    image.GetPointData().SetScalars(density)
    return image


def coarse_grid(cloud):
    """The density averaged over SHRINK^3 voxels, placed at their centres."""
    shrink = vtkImageShrink3D()
    shrink.SetInputData(cloud)
    shrink.SetShrinkFactors(SHRINK, SHRINK, SHRINK)
    shrink.AveragingOn()
    # vtkImageShrink3D keeps the origin, but the mean of fine voxels
    # 3i..3i+2 belongs at their centre, one fine voxel further.
    centre = vtkImageChangeInformation()
    centre.SetInputConnection(shrink.GetOutputPort())
    centre.SetOriginTranslation([(SHRINK - 1) / 2.0 * s for s in cloud.GetSpacing()])
    centre.Update()
    coarse = centre.GetOutput()
    coarse.GetPointData().GetScalars().SetName("density")
    return coarse


def solve(coarse, cloud, light, threads):
    """Lights the coarse cloud; returns G (3 components) baked onto the fine grid."""
    norm = math.sqrt(sum(c * c for c in light))
    scene = {
        "version": 1,
        "channels": 3,
        "material": {"preset": "cloud"},
        "boundary": {"zmax": {"type": "open", "radiance": SKY_RADIANCE}},
        "lights": [{"type": "directional", "direction": [c / norm for c in light],
                    "irradiance": SUN_IRRADIANCE}],
        "solver": {"method": "dense"},
    }
    lit = lit_grid.solve(coarse, scene, threads, "cloud")
    return lit_grid.bake(lit, cloud)


def extinction_per_km(coarse):
    """The preset's extinction at density 1 (1/km): 0.5 per solve-grid voxel
    at the solve grid's largest density ("relative": its scalar range,
    which starts at 0, the domain's edges being empty)."""
    lo, hi = coarse.GetScalarRange()
    return OPTICAL_DEPTH_PER_VOXEL / coarse.GetSpacing()[0] / (hi - lo)


def render_ready_rgba(cloud, G, kappa_per_density):
    """RGBA unsigned char: RGB = 255 albedo x G / G_WHITE (the cloud is
    white), A = 255 x the opacity of OPACITY_UNIT km."""
    rgb = vtkImageShiftScale()
    rgb.SetInputData(G)
    rgb.SetScale(255.0 * ALBEDO / G_WHITE)
    rgb.SetOutputScalarTypeToUnsignedChar()
    rgb.ClampOverflowOn()

    # 1 - exp(-kappa OPACITY_UNIT), kappa = kappa_per_density x density.
    alpha = vtkImageData()
    alpha.CopyStructure(cloud)
    alpha.AllocateScalars(VTK_FLOAT, 1)
    density = cloud.GetPointData().GetScalars()
    values = alpha.GetPointData().GetScalars()
    for n in range(density.GetNumberOfTuples()):
        values.SetValue(n, 255.0 * (1.0 - math.exp(-kappa_per_density * density.GetValue(n)
                                                    * OPACITY_UNIT)))
    alpha_byte = vtkImageShiftScale()
    alpha_byte.SetInputData(alpha)
    alpha_byte.SetOutputScalarTypeToUnsignedChar()
    alpha_byte.ClampOverflowOn()

    rgba = vtkImageAppendComponents()
    rgba.AddInputConnection(rgb.GetOutputPort())
    rgba.AddInputConnection(alpha_byte.GetOutputPort())
    rgba.Update()
    return rgba.GetOutput()


def volume_picture(cloud, G, kappa_per_density, size, path):
    """(a) Emission-absorption volume rendering of the baked light: colour =
    albedo x G, opacity from the extinction, seen from the south (-y) a
    little below the cloud's middle, the sun on the left."""
    volume = rgba_volume(render_ready_rgba(cloud, G, kappa_per_density), OPACITY_UNIT,
                         SIZE_KM / FINE / 2)
    renderer = vtkRenderer()
    # A sky behind it: deep blue above, paler at the horizon.
    renderer.GradientBackgroundOn()
    renderer.SetBackground(0.45, 0.6, 0.8)     # bottom
    renderer.SetBackground2(0.1, 0.25, 0.55)   # top
    renderer.AddVolume(volume)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    fp = camera.GetFocalPoint()
    camera.SetPosition(fp[0], fp[1] - camera.GetDistance(), fp[2])
    camera.SetViewUp(0, 0, 1)
    camera.Azimuth(20.0)
    camera.Elevation(-10.0)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera()
    camera.Zoom(1.5)
    write_png([renderer], size, path)


def slice_picture(cloud, G_lum, size, path):
    """(b) G on the vertical slice through the cloud's middle (y = 1.5 km,
    log colour scale), seen from the south (-y), the sun on the left, with
    the cloud's outline."""
    j = FINE // 2
    y = cloud.GetOrigin()[1] + j * cloud.GetSpacing()[1]
    lut = colour_ramp(((0.0, 0.0, 0.0, 0.02), (0.25, 0.26, 0.04, 0.41), (0.5, 0.73, 0.21, 0.33),
                       (0.75, 0.98, 0.55, 0.04), (1.0, 0.99, 1.0, 0.64)),
                      SLICE_RANGE, log=True)
    mapper = vtkImageSliceMapper()
    mapper.SetInputData(G_lum)
    mapper.SetOrientationToY()
    mapper.SetSliceNumber(j)
    image = vtkImageSlice()
    image.SetMapper(mapper)
    image.GetProperty().SetLookupTable(lut)
    image.GetProperty().UseLookupTableScalarRangeOn()
    image.GetProperty().SetInterpolationTypeToLinear()

    background = (0.1, 0.1, 0.12)
    renderer = vtkRenderer()
    renderer.SetBackground(*background)
    renderer.AddViewProp(image)
    # The outline: the density isosurface cut by the slice plane, moved 10 m
    # towards the camera (at -y) so that it is drawn over the image.
    surface = vtkFlyingEdges3D()
    surface.SetInputData(cloud)
    surface.SetValue(0, OUTLINE * cloud.GetScalarRange()[1])
    surface.ComputeNormalsOff()
    plane = vtkPlane()
    plane.SetOrigin(0.0, y, 0.0)
    plane.SetNormal(0.0, 1.0, 0.0)
    cut = vtkCutter()
    cut.SetInputConnection(surface.GetOutputPort())
    cut.SetCutFunction(plane)
    toward_camera = vtkTransform()
    toward_camera.Translate(0.0, -0.01, 0.0)
    move = vtkTransformPolyDataFilter()
    move.SetInputConnection(cut.GetOutputPort())
    move.SetTransform(toward_camera)
    line_mapper = vtkPolyDataMapper()
    line_mapper.SetInputConnection(move.GetOutputPort())
    line_mapper.ScalarVisibilityOff()
    lines = vtkActor()
    lines.SetMapper(line_mapper)
    lines.GetProperty().SetColor(0.55, 0.8, 1.0)
    lines.GetProperty().SetLineWidth(1.0)
    lines.GetProperty().LightingOff()
    renderer.AddActor(lines)

    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    fp = camera.GetFocalPoint()
    camera.SetFocalPoint(fp[0], y, fp[2])
    camera.SetPosition(fp[0], y - camera.GetDistance(), fp[2])
    camera.SetViewUp(0, 0, 1)
    camera.ParallelProjectionOn()
    renderer.ResetCamera()
    # The whole slice in the scene's viewport (80% of the width).
    aspect = 0.8 * size[0] / size[1]
    camera.SetParallelScale(0.51 * max(SIZE_KM, SIZE_KM / aspect))
    labels = vtkDoubleArray()
    for v in (0.1, 1.0):
        labels.InsertNextValue(v)
    write_png(with_scalar_bar(renderer, lut, "G (W/m2)", background, labels), size, path)


def main():
    args = parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    start = time.time()
    cloud = make_cloud()
    coarse = coarse_grid(cloud)
    kappa = extinction_per_km(coarse)
    print(f"cloud: {cloud.GetDimensions()} voxels of {cloud.GetSpacing()[0] * 1000:.0f} m, solved on "
          f"{coarse.GetDimensions()}; extinction {kappa:.2f}/km at density 1, albedo {ALBEDO}")
    G = solve(coarse, cloud, args.light, args.threads)
    G_lum = luminance(G)
    print(f"baked G onto {G.GetDimensions()}: {G_lum.GetScalarRange()[0]:.3f} .. "
          f"{G_lum.GetScalarRange()[1]:.3f} W/m^2 ({time.time() - start:.1f} s)")
    volume_picture(cloud, G, kappa, args.size, os.path.join(args.outdir, "cloud_volume.png"))
    slice_picture(cloud, G_lum, args.size, os.path.join(args.outdir, "cloud_slice.png"))
    print(f"done in {time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
