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
import math
import os
import time

# Factories of the OpenGL render window and of the volume mapper's display
# helper (without them, vtkRenderWindow() is an abstract object).
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderer

# The picture helpers (same folder, shared with ct_head.py and frog_labels.py)
# and the RGBA volume (see rgba_volume.py for the VTK 9.1 bug it avoids).
import lit_grid
import pictures
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
    return pictures.parse_args("Light a procedural cloud and render two PNGs.", LIGHT_DIRECTION,
                         "direction the sunlight travels")


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
    return pictures.named_output(lit_grid.average(cloud, SHRINK), "density")


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


def volume_picture(cloud, G, kappa_per_density, size, path):
    """(a) Emission-absorption volume rendering of the baked light: colour =
    albedo x G, opacity from the extinction, seen from the south (-y) a
    little below the cloud's middle, the sun on the left."""
    rgba = pictures.scattering_rgba(cloud, G, ALBEDO / G_WHITE, kappa_per_density, OPACITY_UNIT)
    volume = rgba_volume(rgba, OPACITY_UNIT, SIZE_KM / FINE / 2)
    renderer = vtkRenderer()
    # A sky behind it: deep blue above, paler at the horizon.
    renderer.GradientBackgroundOn()
    renderer.SetBackground(0.45, 0.6, 0.8)     # bottom
    renderer.SetBackground2(0.1, 0.25, 0.55)   # top
    renderer.AddVolume(volume)
    pictures.orbit_camera(renderer, 1, -1.0, (0, 0, 1), azimuth=20.0, elevation=-10.0, zoom=1.5)
    pictures.write_png([renderer], size, path)


def slice_picture(cloud, G_lum, size, path):
    """(b) G on the vertical slice through the cloud's middle (y = 1.5 km,
    log colour scale), seen from the south (-y), the sun on the left, with
    the cloud's outline."""
    j = FINE // 2
    y = cloud.GetOrigin()[1] + j * cloud.GetSpacing()[1]
    renderer, lut = pictures.slice_scene(G_lum, 1, j, SLICE_RANGE)
    # The outline: the density isosurface cut by the slice plane, moved 10 m
    # towards the camera (at -y) so that it is drawn over the image.
    surface = pictures.isosurface(cloud, OUTLINE * cloud.GetScalarRange()[1])
    renderer.AddActor(pictures.outline(surface, 1, y, -0.01))
    # The whole slice in the scene's viewport.
    pictures.slice_camera(renderer, 1, -1.0, (0, 0, 1), SIZE_KM, SIZE_KM, size, at=y)
    pictures.write_slice_png(renderer, lut, (0.1, 1.0), size, path)


def main():
    args = parse_args()
    start = time.time()
    cloud = make_cloud()
    coarse = coarse_grid(cloud)
    kappa = extinction_per_km(coarse)
    print(f"cloud: {cloud.GetDimensions()} voxels of {cloud.GetSpacing()[0] * 1000:.0f} m, solved on "
          f"{coarse.GetDimensions()}; extinction {kappa:.2f}/km at density 1, albedo {ALBEDO}")
    G = solve(coarse, cloud, args.light, args.threads)
    G_lum = pictures.baked_luminance(G, start)
    volume_picture(cloud, G, kappa, args.size, os.path.join(args.outdir, "cloud_volume.png"))
    slice_picture(cloud, G_lum, args.size, os.path.join(args.outdir, "cloud_slice.png"))
    print(f"done in {time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
