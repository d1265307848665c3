"""Lights a volume with vtkVolumetricRadiosity, in the style of a ParaView script.

    PYTHONPATH=build/lib/python3/dist-packages python3 Examples/Python/light_volume.py \
        [--dense] [-o OUTPUT.vti] [INPUT.vti [SCENE.json]]

Defaults to the bundled Data/neghip16.vti and Data/neghip16.scene.json.
The scene's solver (hierarchical by default) takes about a minute on
neghip16; --dense selects the dense solver instead (a few seconds there).
"""
import argparse
import json
import os
import sys

from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter

from volrad import vtkVolumetricRadiosity

data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data")
parser = argparse.ArgumentParser(description="Light a .vti volume with volumetric radiosity.")
parser.add_argument("input", nargs="?", default=os.path.join(data, "neghip16.vti"))
parser.add_argument("scene", nargs="?", default=os.path.join(data, "neghip16.scene.json"))
parser.add_argument("-o", "--output", help="write the lit volume to this .vti")
parser.add_argument("--dense", action="store_true", help="use the dense solver")
args = parser.parse_args()

# Read the volume: point arrays kappa_a, sigma_i, E_I (named by the scene).
reader = vtkXMLImageDataReader()
reader.SetFileName(args.input)

radiosity = vtkVolumetricRadiosity()
radiosity.SetInputConnection(reader.GetOutputPort())
if args.dense:
    # Same scene, other solver: the filter takes the scene as JSON text too.
    with open(args.scene) as f:
        scene = json.load(f)
    scene.setdefault("solver", {})["method"] = "dense"
    radiosity.SetSceneJSON(json.dumps(scene))
else:
    radiosity.SetSceneFileName(args.scene)
radiosity.Update()

lit = radiosity.GetOutput()
G = lit.GetPointData().GetArray("IncidentRadiation")
if G is None:
    # The filter has reported the cause as a VTK error (on stderr).
    sys.exit("light_volume: the solve failed, no output")

# The solve's statistics are in the output's field data.
fd = lit.GetFieldData()
residual = fd.GetArray("EnergyBalanceResidual")
print(f"solver {fd.GetAbstractArray('SolverMethod').GetValue(0)}, "
      f"{fd.GetArray('SolveSeconds').GetValue(0):.2f} s")
print("energy balance residual per channel:",
      " ".join(f"{residual.GetComponent(0, c):.3g}" for c in range(residual.GetNumberOfComponents())))
print(f"IncidentRadiation ({lit.GetNumberOfPoints()} points, W/m^2) per channel:")
for c in range(G.GetNumberOfComponents()):
    lo, hi = G.GetRange(c)
    print(f"  channel {c}: {lo:.6g} .. {hi:.6g}")

if args.output:
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(args.output)
    writer.SetInputData(lit)
    if not writer.Write():
        sys.exit(f"light_volume: could not write {args.output}")
    print(f"wrote {args.output}")
