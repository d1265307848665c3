"""Lights the CT head in ParaView and saves a volume rendering of it.

    pvpython --force-offscreen-rendering Examples/ParaView/ct_head.py \
        [OUTDIR] [--plugin build-paraview/lib/paraview-plugins/VolRad/VolRad.so]

A ParaView-style script (paraview.simple, as a ParaView Python trace writes
them; pvbatch runs it too): loads the VolRad plugin, reads the CT head
(Data/headsq/quarter.nhdr, 64x64x93 voxels of stored CT values, HU + 1024),
lights it with the Volumetric Radiosity filter (ct material, one white
directional light, RGB) on a grid 4 times coarser, bakes the incident
radiation G back onto the full-resolution volume and volume-renders it:
colour = G (the light that reached each voxel, after every bounce), opacity
= the CT values (separate opacity array), so bright tissue is lit tissue and
the shadowed side of the head is dark. Writes OUTDIR/paraview_ct_head.png
(default OUTDIR: out/), 400x400 (the regression test's baseline size). About 30 s on 2 cores, most of it the
solve.

Without --plugin, the plugin is taken from PV_PLUGIN_PATH (ParaView loads
the plugins there at start-up) or from build-paraview/ in this source tree.
"""
import argparse
import os
import sys
import time

from paraview.simple import (
    Calculator,
    CreateRenderView,
    GetColorTransferFunction,
    GetOpacityTransferFunction,
    LoadPlugin,
    OpenDataFile,
    PassArrays,
    ResampleToImage,
    ResampleWithDataset,
    SaveScreenshot,
    Show,
)
import paraview.simple

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "..")
DATA = os.path.join(SOURCE, "Data", "headsq", "quarter.nhdr")
BUILT_PLUGIN = os.path.join(SOURCE, "build-paraview", "lib", "paraview-plugins", "VolRad", "VolRad.so")

# The light: direction it travels (x, y, z) and irradiance (r, g, b) [W/m^2]
# (the bundled Data/headsq.scene.json's).
LIGHT = [0.85, -0.45, 0.25, 1.0, 1.0, 1.0]


def load_plugin(path):
    """Defines VolumetricRadiosity in paraview.simple (once per session)."""
    if hasattr(paraview.simple, "VolumetricRadiosity"):
        return  # loaded from PV_PLUGIN_PATH at start-up
    path = path or BUILT_PLUGIN
    if not os.path.isfile(path):
        sys.exit(f"ct_head.py: no VolRad plugin at {path}: build it with "
                 "scripts/build-paraview.sh, or give --plugin or PV_PLUGIN_PATH")
    LoadPlugin(path, ns=vars(paraview.simple))


def light_ct_head(size=(400, 400), threads=0):
    """The pipeline: returns the render view, ready to save."""
    reader = OpenDataFile(DATA)
    scalars = reader.PointData.keys()[0]  # ImageFile: stored CT values

    # Radiosity is smooth: solve on a coarse grid (16x16x24 voxels), bake back.
    coarse = ResampleToImage(Input=reader)
    coarse.SamplingDimensions = [16, 16, 24]
    lit = paraview.simple.VolumetricRadiosity(Input=coarse)
    lit.MaterialScalars = scalars
    lit.MaterialPreset = "ct"
    lit.RescaleIntercept = -1024.0  # stored value -> Hounsfield units
    lit.DirectionalLights = LIGHT
    lit.Channels = 1
    # The dense solver is the faster one at this size (seconds, not a minute).
    lit.SolverMethod = "dense"
    lit.NumberOfThreads = threads
    light = PassArrays(Input=lit)
    light.PointDataArrays = ["IncidentRadiation"]
    baked = ResampleWithDataset(SourceDataArrays=light, DestinationMesh=reader)
    baked.PassPointArrays = 1  # keep the full-resolution CT values

    view = CreateRenderView()
    view.ViewSize = list(size)
    view.OrientationAxesVisibility = 0
    view.Background = [0.1, 0.1, 0.12]
    try:  # ParaView 5.11: the background is the palette's unless told otherwise
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    # Colour: G in mW/m^2. (ParaView 5.11's GPU volume mapper on Mesa renders
    # a colour map over small values, such as G's 0-2 W/m^2, black: so the
    # colour array is in milliwatts.) The map's nodes are fractions of the
    # largest G, nearly logarithmic: G falls by decades into the head.
    baked.UpdatePipeline()
    g_max = 1000.0 * baked.PointData["IncidentRadiation"].GetRange(-1)[1]
    light_level = Calculator(Input=baked)
    light_level.ResultArrayName = "G_mW"
    light_level.Function = "1000 * IncidentRadiation"
    display = Show(light_level, view)
    display.Representation = "Volume"
    display.ColorArrayName = ["POINTS", "G_mW"]
    colours = GetColorTransferFunction("G_mW")
    nodes = [(0.0, (0.0, 0.0, 0.0)),  # black: no light
             (0.01, (0.35, 0.05, 0.1)),
             (0.05, (0.9, 0.3, 0.1)),
             (0.2, (1.0, 0.8, 0.4)),
             (0.6, (1.0, 1.0, 0.9)),  # white: where the light enters
             (1.0, (1.0, 1.0, 1.0))]
    colours.RGBPoints = [v for f, rgb in nodes for v in (f * g_max, *rgb)]
    # Opacity from the tissue (a separate opacity array): air clear, soft
    # tissue faint, bone dense.
    display.UseSeparateOpacityArray = 1
    display.OpacityArrayName = ["POINTS", scalars]
    opacity = GetOpacityTransferFunction(scalars)
    opacity.Points = [0, 0, 0.5, 0,  # x, opacity, midpoint, sharpness
                      600, 0, 0.5, 0,
                      1000, 0.02, 0.5, 0,
                      1300, 0.15, 0.5, 0,
                      2500, 0.8, 0.5, 0]
    display.ScalarOpacityFunction = opacity
    display.ScalarOpacityUnitDistance = 3.2

    # Facing the head, turned a little (as Examples/Python/ct_head.py looks).
    view.ResetCamera()
    camera = view.GetActiveCamera()
    focal = list(camera.GetFocalPoint())
    camera.SetPosition(focal[0], focal[1] + camera.GetDistance(), focal[2])
    camera.SetViewUp(0.0, 0.0, -1.0)
    camera.Azimuth(-20.0)
    camera.Elevation(-10.0)
    camera.OrthogonalizeViewUp()
    view.ResetCamera()
    camera.Zoom(1.3)
    return view


def save_picture(output_dir, size=(400, 400), threads=0, plugin=None):
    """Runs the pipeline and writes OUTDIR/paraview_ct_head.png; returns its path."""
    load_plugin(plugin)
    view = light_ct_head(size, threads)
    os.makedirs(output_dir, exist_ok=True)
    path = os.path.join(output_dir, "paraview_ct_head.png")
    SaveScreenshot(path, view, ImageResolution=list(size))
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output_dir", nargs="?", default="out")
    parser.add_argument("--plugin", help="the VolRad plugin (VolRad.so)")
    parser.add_argument("--size", type=int, nargs=2, default=[400, 400], metavar=("W", "H"))
    parser.add_argument("--threads", type=int, default=0)
    args = parser.parse_args()
    start = time.time()
    path = save_picture(args.output_dir, args.size, args.threads, args.plugin)
    print(f"wrote {path} ({time.time() - start:.0f} s)")


if __name__ == "__main__":
    main()
