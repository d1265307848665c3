"""Lights a smoke plume from an OpenVDB file with the sun and a blue sky,
writes the lighting back as OpenVDB grids and renders two pictures.

    PYTHONPATH=build/lib/python3/dist-packages \
        xvfb-run -a /usr/bin/python3 Examples/Python/smoke.py [OUTDIR] [--vdb FILE] [--size W H]

Reads the `density` grid of Data/smoke/smoke.vdb (OpenVDB's "smoke1"
sample: 1.05 M active voxels in a 111x222x112 box of voxel size 0.476, the
plume rising along +y) with vtkOpenVDBGridReader, averages it 2x2x2 for the
pictures (55x111x56) and 8x8x8 for the solve (13x27x14), maps it with the
"cloud" material preset (albedo 0.99, white, isotropic) but an extinction of
0.25 per unit length at density 1 (the sample's densities reach 6: up to
1.5 per unit, about 6 optical depths per solve voxel in the dense foot of
the plume, 0.1-1 in its upper part), lights it with
vtkVolumetricRadiosity (a white sun from the upper left, a blue sky through
the top face, y = max; RGB) and writes to OUTDIR (default out/):

  smoke-lit.vdb      OpenVDB grids on the pictures' grid: density and the
                     baked IncidentRadiation (vec3s, RGB), for Houdini,
                     Blender or any OpenVDB tool (vtkOpenVDBGridWriter)
  smoke_volume.png   volume rendering: colour = albedo x G, opacity =
                     extinction, over a sky-coloured background
  smoke_slice.png    G on the slice z = middle (log scale), the plume's
                     outline drawn

--size W H sets the pictures' size (default 400 400, the size of the
regression test's baselines), --light DX DY DZ the direction the sunlight
travels, --threads the solver's threads. About 20 s on 2 cores.

Only the grid's active box is read: the empty space around the plume in the
file costs nothing. The solve itself still covers the box (its voxels
without smoke are light's paths, not unknowns: they cost the views of G).
"""
import math
import os
import time

import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderer

import lit_grid
import pictures
from rgba_volume import rgba_volume
from volrad import vtkOpenVDBGridReader, vtkOpenVDBGridWriter

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data", "smoke",
                    "smoke.vdb")
FINE_SHRINK = 2            # the pictures' grid: the file's voxels averaged 2x2x2
SOLVE_SHRINK = 4           # the solve's grid: the pictures' averaged 4x4x4
EXTINCTION_PER_DENSITY = 0.25  # per unit length at density 1
ALBEDO = 0.99
# Direction the sunlight travels: from the upper left of the pictures (-x,
# +y), a little from the viewer's side (+z).
LIGHT_DIRECTION = [0.6, -0.7, -0.3]
SUN_IRRADIANCE = 1.0                    # on a plane normal to the sun, white
SKY_RADIANCE = [0.02, 0.04, 0.08]       # entering through the top (y = max)
G_WHITE = 2.0              # G shown at full brightness (display exposure)
OPACITY_UNIT = 2.0         # the volume's alpha is the opacity of 2 length units
OUTLINE = 0.03             # the plume's outline on the slice, fraction of the peak density
SLICE_RANGE = (0.05, 2.5)  # G on the slice, log scale


def parse_args():
    return pictures.parse_args("Light OpenVDB's smoke sample and render two PNGs.",
                               LIGHT_DIRECTION, "direction the sunlight travels")


def read_density(path):
    """The density grid over its active box (the file's voxels)."""
    reader = vtkOpenVDBGridReader()
    reader.SetFileName(path)
    reader.SetGridName("density")
    reader.Update()
    image = reader.GetOutput()
    if image.GetNumberOfPoints() == 0:
        raise SystemExit(f"smoke: cannot read the density grid of {path} (see the VTK error above)")
    lo, hi = image.GetScalarRange()
    print(f"read {path}: {image.GetDimensions()} voxels of {image.GetSpacing()[0]:.3f}, "
          f"density {lo:.0f} .. {hi:.0f}")
    return image


def write_vdb(density, G, path):
    """density and G on one grid as OpenVDB grids (empty voxels inactive)."""
    both = vtkImageData()
    both.CopyStructure(density)
    both.GetPointData().AddArray(density.GetPointData().GetScalars())
    both.GetPointData().AddArray(G.GetPointData().GetScalars())
    writer = vtkOpenVDBGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(both)
    writer.AddArrayName("density")
    writer.AddArrayName("IncidentRadiation")
    if writer.Write() != 1:
        raise SystemExit(f"smoke: cannot write {path} (see the VTK error above)")
    print(f"wrote {path} (OpenVDB grids density and IncidentRadiation)")


def volume_picture(fine, G, kappa_per_density, size, path):
    """Volume rendering of the baked light seen from +z (x to the right, y
    up), the sun on the upper left, over a sky."""
    rgba = pictures.scattering_rgba(fine, G, ALBEDO / G_WHITE, kappa_per_density, OPACITY_UNIT)
    volume = rgba_volume(rgba, OPACITY_UNIT, fine.GetSpacing()[0] / 2)
    renderer = vtkRenderer()
    renderer.GradientBackgroundOn()
    renderer.SetBackground(0.45, 0.6, 0.8)     # bottom
    renderer.SetBackground2(0.1, 0.25, 0.55)   # top
    renderer.AddVolume(volume)
    pictures.orbit_camera(renderer, 2, 1.0, (0, 1, 0), azimuth=-15.0, elevation=5.0, zoom=1.1)
    pictures.write_png([renderer], size, path)


def slice_picture(fine, G_lum, size, path):
    """G on the slice through the plume's middle (z), seen from +z, with
    the plume's outline."""
    k = fine.GetDimensions()[2] // 2
    z = fine.GetOrigin()[2] + k * fine.GetSpacing()[2]
    renderer, lut = pictures.slice_scene(G_lum, 2, k, SLICE_RANGE)
    surface = pictures.isosurface(fine, OUTLINE * fine.GetScalarRange()[1])
    renderer.AddActor(pictures.outline(surface, 2, z, 0.2))
    bounds = fine.GetBounds()
    pictures.slice_camera(renderer, 2, 1.0, (0, 1, 0), bounds[3] - bounds[2],
                          bounds[1] - bounds[0], size, at=z)
    pictures.write_slice_png(renderer, lut, (0.1, 1.0), size, path)


def main():
    args = parse_args()
    start = time.time()
    path = os.environ.get("VOLRAD_SMOKE_VDB", DATA)
    density = read_density(path)
    fine = pictures.named_output(lit_grid.average(density, FINE_SHRINK), "density")
    coarse = pictures.named_output(lit_grid.average(fine, SOLVE_SHRINK), "density")
    kappa = EXTINCTION_PER_DENSITY
    print(f"smoke: pictures on {fine.GetDimensions()}, solved on {coarse.GetDimensions()}; "
          f"extinction {kappa} per unit length at density 1, albedo {ALBEDO}")
    norm = math.sqrt(sum(c * c for c in args.light))
    scene = {
        "version": 1,
        "channels": 3,
        # The preset's albedo and colour, the extinction linear in density
        # (the function's last point is past the sample's densest voxel).
        "material": {"preset": "cloud", "relative": False, "per_voxel": False,
                     "extinction": [[0.0, 0.0], [8.0, 8.0 * EXTINCTION_PER_DENSITY]]},
        "boundary": {"ymax": {"type": "open", "radiance": SKY_RADIANCE}},
        "lights": [{"type": "directional", "direction": [c / norm for c in args.light],
                    "irradiance": SUN_IRRADIANCE}],
        "solver": {"method": "dense"},
    }
    lit = lit_grid.solve(coarse, scene, args.threads, "smoke")
    G = lit_grid.bake(lit, fine)
    write_vdb(fine, G, os.path.join(args.outdir, "smoke-lit.vdb"))
    volume_picture(fine, G, kappa, args.size, os.path.join(args.outdir, "smoke_volume.png"))
    slice_picture(fine, pictures.baked_luminance(G, start), args.size,
                  os.path.join(args.outdir, "smoke_slice.png"))
    print(f"done in {time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
