"""Lights the VTK frog's tissue segmentation through a label table and renders two pictures.

    PYTHONPATH=build/lib/python3/dist-packages \
        xvfb-run -a /usr/bin/python3 Examples/Python/frog_labels.py [OUTDIR] [--size W H]

Reads Data/frogtissue/frogtissue.mhd (the segmented frog of the VTK
textbook: 500x470x136 voxels of 1x1x1.5 mm, one label per voxel), gives each
tissue an optical material with a label table (the scene file's
"material": {"labels": {...}}), lights it with one white directional light
through vtkVolumetricRadiosity (RGB, dense solver) and writes to OUTDIR
(default: out/):

  frog_labels_volume.png  volume rendering: colour = the label's albedo
                          colour x baked G, opacity = the label's extinction
  frog_labels_slice.png   G on a cross-section of the body through the heart,
                          liver and stomach (log scale), the tissue
                          boundaries outlined

--size W H sets the pictures' size (default 400 400, the size of the
regression test's baselines), --light DX DY DZ the direction the light
travels, --threads the solver's threads. About 20 s on 2 cores, most of it
the solve.

The frog lies in the x-y plane: its head towards +x (brain and eyes at
x = 360-430 mm), its legs spread out in that plane, its back towards z = 0
(-z is up). The
segmentation has the internal organs and the skeleton but no skin or
muscle (VTK's examples take the skin from the greyscale frog.mhd): the
lit organs hang in empty space, and they and the skeleton shadow each other.

Labels (VTK's frog tissues, the colours those of the textbook's frog lookup
table, as albedo colours): 1 blood, 2 brain, 3 duodenum, 4 eye retina, 5 eye
white, 6 heart, 7 ileum, 8 kidney, 9 large intestine, 10 liver, 11 lung,
12 nerve, 13 skeleton, 14 spleen, 15 stomach. Labels 16-29 are unnamed
fragments (800 voxels in all) and, like the lung (air) and the
background, are left empty.

Lighting on a coarse grid, baked back: the dense solver handles about 20^3
voxels, so the frog is solved on a grid of 20x20x16.5 mm voxels (23x23x12)
and G is interpolated back onto a 2x subsampled grid (2x2x3 mm, 230x230x66)
for the pictures. A label table needs labels on the coarse grid, and
averaging labels is meaningless (the mean of liver and skeleton is not
kidney), so the coarse grid takes, like vtkImageShrink3D with averaging
off, one voxel's label per block: the one nearest the block's centre
(vtkImageReslice, nearest neighbour, its output grid placed on the blocks'
centres, so there is no origin to correct). That keeps each tissue's volume
fraction on average, while thin structures (vessels, nerves, the finer
bones) come out patchy: the coarse light carries the large-scale shadows of
the organs, the full detail comes from the labels it multiplies.
"""
import math
import os
import time

# Factories of the OpenGL render window and of the volume mapper's display
# helper (without them, vtkRenderWindow() is an abstract object).
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkFiltersGeneral import vtkDiscreteFlyingEdges3D
from vtkmodules.vtkImagingCore import (
    vtkImageExtractComponents,
    vtkImageMapToColors,
    vtkImageReslice,
)
from vtkmodules.vtkIOImage import vtkMetaImageReader
from vtkmodules.vtkRenderingCore import vtkRenderer

# The picture helpers (same folder, shared with ct_head.py and cloud.py) and
# the RGBA volume (see rgba_volume.py for the VTK 9.1 bug it avoids).
import lit_grid
import pictures
from rgba_volume import rgba_volume

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "Data", "frogtissue", "frogtissue.mhd")

# label: (tissue, extinction kappa_t [1/mm], albedo, colour). The colours are
# those of VTK's frog lookup table (vtkNamedColors, named in the comments),
# used as the albedo's colour: what white light keeps when it scatters in the
# tissue. Soft organs scatter strongly (albedo 0.92-0.97) with a mean free
# path of 12-20 mm, as the ct material's soft tissue (real tissue: 0.1 mm, which
# would make the frog opaque); blood, liver and heart absorb more; the eye's
# white is a dense white scatterer and the skeleton the densest, whitish
# tissue. The lung (air) is left out, hence empty.
TISSUES = {
    1: ("blood", 0.10, 0.90, (0.980, 0.502, 0.447)),          # salmon
    2: ("brain", 0.05, 0.97, (0.961, 0.961, 0.863)),          # beige
    3: ("duodenum", 0.05, 0.95, (1.000, 0.647, 0.000)),       # orange
    4: ("eye retina", 0.10, 0.90, (1.000, 0.894, 0.882)),     # misty_rose
    5: ("eye white", 0.20, 0.98, (1.000, 1.000, 1.000)),      # white
    6: ("heart", 0.08, 0.92, (1.000, 0.388, 0.278)),          # tomato
    7: ("ileum", 0.05, 0.95, (0.529, 0.149, 0.341)),          # raspberry
    8: ("kidney", 0.06, 0.94, (0.890, 0.812, 0.341)),         # banana
    9: ("large intestine", 0.05, 0.95, (0.804, 0.522, 0.247)),  # peru
    10: ("liver", 0.08, 0.92, (1.000, 0.753, 0.796)),         # pink
    12: ("nerve", 0.05, 0.97, (0.929, 0.569, 0.129)),         # carrot
    13: ("skeleton", 0.30, 0.95, (0.961, 0.871, 0.702)),      # wheat
    14: ("spleen", 0.06, 0.93, (0.933, 0.510, 0.933)),        # violet
    15: ("stomach", 0.05, 0.95, (0.867, 0.627, 0.867)),       # plum
}
MAX_LABEL = 29

# The box the frog occupies (labels at x 27-475, y 12-469, z 1-131, in
# voxels of the file) cut into blocks of 20x20x11 voxels: the solve's grid,
# 23x23x12 voxels of 20x20x16.5 mm (6348 voxels, the dense solver's size).
BOX_START = (21, 10, 0)            # first voxel of the box, in the file's voxels
BLOCK = (20, 20, 11)               # voxels of the file per coarse voxel
COARSE_DIMS = (23, 23, 12)
RENDER_STEP = (2, 2, 2)            # the pictures' grid: every other voxel
# Direction the light travels: from the frog's +y side, from above (its
# back, -z) and a little from the head (+x), so that the -y side of the body
# lies in the shadow of its organs.
LIGHT_DIRECTION = [-0.3, -0.75, 0.6]
IRRADIANCE = 1.0           # W/m^2 on a plane normal to the light
G_WHITE = 1.0              # G shown at full brightness (display exposure)
OPACITY_UNIT = 4.0         # mm: the volume's alpha is the opacity of 4 mm
VIEW_TILT = -35.0          # degrees the view of the volume turns from above towards -y
SLICE_X = 250.0            # mm: the cross-section through the heart, liver, lungs and stomach
SLICE_RANGE = (1e-2, 1.5)  # G on the slice, log scale


def parse_args():
    return pictures.parse_args("Light the frog's tissue labels and render two PNGs.",
                               LIGHT_DIRECTION)


def read_labels():
    reader = vtkMetaImageReader()
    reader.SetFileName(DATA)
    return pictures.named_output(reader, "Tissue")


def sample(labels, step, count):
    """The labels of the box on a grid of `step` voxels per voxel, `count`
    voxels along each axis, each the label of the file's voxel nearest the
    centre of its block (no averaging: labels are categories)."""
    spacing = labels.GetSpacing()
    origin = labels.GetOrigin()
    reslice = vtkImageReslice()
    reslice.SetInputData(labels)
    reslice.SetOutputSpacing([step[a] * spacing[a] for a in range(3)])
    reslice.SetOutputOrigin([origin[a] + (BOX_START[a] + (step[a] - 1) / 2.0) * spacing[a]
                             for a in range(3)])
    reslice.SetOutputExtent(0, count[0] - 1, 0, count[1] - 1, 0, count[2] - 1)
    reslice.SetInterpolationModeToNearestNeighbor()
    return pictures.named_output(reslice, "Tissue")


def label_table():
    """The scene file's label table."""
    return {str(label): {"extinction": kappa, "albedo": albedo, "color": list(colour)}
            for label, (name, kappa, albedo, colour) in TISSUES.items()}


def solve(coarse, fine, light, threads):
    """Lights the coarse labels; returns G (3 components) baked onto `fine`'s grid."""
    norm = math.sqrt(sum(c * c for c in light))
    scene = {
        "version": 1,
        "channels": 3,
        "material": {"labels": label_table()},
        "lights": [{"type": "directional", "direction": [c / norm for c in light],
                    "irradiance": IRRADIANCE}],
        "solver": {"method": "dense"},
    }
    lit = lit_grid.solve(coarse, scene, threads, "frog_labels")
    return lit_grid.bake(lit, fine)


def tissue_lookup():
    """Label -> RGBA: RGB the albedo colour (albedo x colour), A the opacity
    of OPACITY_UNIT mm of the tissue, 1 - exp(-kappa_t OPACITY_UNIT)."""
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(MAX_LABEL + 1)
    lut.SetTableRange(-0.5, MAX_LABEL + 0.5)   # entry i for label i
    for label in range(MAX_LABEL + 1):
        if label in TISSUES:
            name, kappa, albedo, colour = TISSUES[label]
            lut.SetTableValue(label, *(albedo * c for c in colour),
                              1.0 - math.exp(-kappa * OPACITY_UNIT))
        else:
            lut.SetTableValue(label, 0.0, 0.0, 0.0, 0.0)
    return lut


def render_ready_rgba(fine, G):
    """RGBA unsigned char: RGB = 255 albedo colour x G / G_WHITE, A = 255 x the
    opacity of OPACITY_UNIT mm."""
    rgba_table = vtkImageMapToColors()
    rgba_table.SetInputData(fine)
    rgba_table.SetLookupTable(tissue_lookup())
    rgba_table.SetOutputFormatToRGBA()
    albedo_rgb = vtkImageExtractComponents()
    albedo_rgb.SetInputConnection(rgba_table.GetOutputPort())
    albedo_rgb.SetComponents(0, 1, 2)
    rgb = pictures.lit_colour(albedo_rgb, G, G_WHITE)

    alpha = vtkImageExtractComponents()
    alpha.SetInputConnection(rgba_table.GetOutputPort())
    alpha.SetComponents(3)

    return pictures.append_rgba(rgb, alpha)


def volume_picture(fine, G, size, path):
    """(a) Emission-absorption volume rendering of the baked light: colour =
    albedo colour x G, opacity from the tissue's extinction, seen from above
    and the frog's -y side."""
    # CPU ray caster: the same pixels with any OpenGL (the regression test
    # relies on that); see rgba_volume.py for the VTK 9.1 bug it avoids.
    volume = rgba_volume(render_ready_rgba(fine, G), OPACITY_UNIT, 1.0)
    renderer = vtkRenderer()
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.AddVolume(volume)
    # From above (the back, -z), the head (+x) towards the top of the
    # picture, turned down towards the frog's -y side.
    pictures.orbit_camera(renderer, 2, -1.0, (1, 0, 0), azimuth=VIEW_TILT, zoom=1.3)
    pictures.write_png([renderer], size, path)


def slice_picture(fine, G_lum, size, path):
    """(b) G on the cross-section x = SLICE_X (log colour scale), seen from
    behind (the tail, -x): the frog's +y side, where the light comes from,
    on the right and its back up, the tissue boundaries outlined."""
    spacing, origin = fine.GetSpacing(), fine.GetOrigin()
    i = int(round((SLICE_X - origin[0]) / spacing[0]))
    x = origin[0] + i * spacing[0]
    renderer, lut = pictures.slice_scene(G_lum, 0, i, SLICE_RANGE)
    # Outlines: the boundaries between tissues (the labels' surfaces, cut by
    # the slice plane), moved 1 mm towards the camera (at -x) so that they
    # are drawn over the image.
    surfaces = vtkDiscreteFlyingEdges3D()
    surfaces.SetInputData(fine)
    surfaces.GenerateValues(MAX_LABEL, 1, MAX_LABEL)
    surfaces.ComputeNormalsOff()
    surfaces.ComputeScalarsOff()
    renderer.AddActor(pictures.outline(surfaces, 0, x, -1.0))
    # The whole slice in the scene's viewport.
    bounds = fine.GetBounds()
    pictures.slice_camera(renderer, 0, -1.0, (0, 0, -1), bounds[5] - bounds[4], bounds[3] - bounds[2],
                          size, at=x)
    pictures.write_slice_png(renderer, lut, (0.01, 0.1, 1.0), size, path)


def main():
    args = parse_args()
    start = time.time()
    labels = read_labels()
    pictures.print_read(DATA, labels, "labels")
    coarse = sample(labels, BLOCK, COARSE_DIMS)
    fine = sample(labels, RENDER_STEP, [COARSE_DIMS[a] * BLOCK[a] // RENDER_STEP[a] for a in range(3)])
    G = solve(coarse, fine, args.light, args.threads)
    G_lum = pictures.baked_luminance(G, start)
    volume_picture(fine, G, args.size, os.path.join(args.outdir, "frog_labels_volume.png"))
    slice_picture(fine, G_lum, args.size, os.path.join(args.outdir, "frog_labels_slice.png"))
    print(f"done in {time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
