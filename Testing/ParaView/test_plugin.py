"""The VolRad plugin as a ParaView user loads it (PV_PLUGIN_PATH), through
pvpython: every panel property reaches the filter as its scene-file
counterpart does, ParaView's own transfer functions serve as the material,
the walls come out on the second port, and the lighting goes through a
.vdb file with the plugin's writer and reader.

    PV_PLUGIN_PATH=<build-paraview>/lib/paraview-plugins/VolRad pvpython test_plugin.py

Each check compares two routes to the same scene (panel properties against
the scene's JSON), solved by the dense solver on one thread: the fields must
agree to float precision.
"""
import json
import os
import sys
import tempfile

import paraview.simple as pv
from paraview import servermanager

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def incident(proxy):
    data = servermanager.Fetch(proxy)
    array = data.GetPointData().GetArray("IncidentRadiation")
    return [array.GetValue(i) for i in range(array.GetNumberOfValues())]


def agree(a, b):
    """Largest relative difference of two fields."""
    if len(a) != len(b) or not a:
        return float("inf")
    return max(abs(x - y) / max(abs(x), abs(y), 1e-30) for x, y in zip(a, b))


check(hasattr(pv, "VolumetricRadiosity"),
      "PV_PLUGIN_PATH loads the plugin: paraview.simple has VolumetricRadiosity")
if failures:
    sys.exit(1)

wavelet = pv.Wavelet()
wavelet.WholeExtent = [0, 7, 0, 7, 0, 7]  # 8^3 voxels, RTData about 40-280
EXTINCTION = [[30.0, 0.05], [280.0, 0.6]]
common = dict(Input=wavelet, MaterialScalars="RTData", Channels=3, SolverMethod="dense",
              NumberOfThreads=1)

defaults = pv.VolumetricRadiosity(Input=wavelet)
check(list(defaults.DirectionalLights) == [0.5, -0.5, -1.0, 1.0, 1.0, 1.0]
      and defaults.SolverMethod == "hierarchical" and defaults.Channels == "RGB"
      and abs(defaults.Epsilon - 1e-3) < 1e-12 and defaults.MaterialPreset == "none",
      "defaults: one white light, hierarchical solver, RGB, epsilon 1e-3, no preset")

# 1. Lights and faces as panel properties against the same in the scene file.
panel = pv.VolumetricRadiosity(**common)
panel.SceneJSON = json.dumps({"version": 1, "material": {"extinction": EXTINCTION,
                                                         "albedo": [[0.0, 0.8]]}})
panel.DirectionalLights = [0.3, -0.2, -1.0, 2.0, 1.5, 1.0]
panel.PointLights = [3.5, 3.5, 3.0, 0.3, 0.2, 0.1]
panel.OpenFaces = [5, 0.1, 0.2, 0.3]
panel.WallFaces = [4, 0.5, 0.4, 0.3, 0.0, 0.0, 1.0]
scene = pv.VolumetricRadiosity(**common)
scene.DirectionalLights = []
scene.SceneJSON = json.dumps({
    "version": 1, "channels": 3,
    "material": {"extinction": EXTINCTION, "albedo": [[0.0, 0.8]]},
    "boundary": {"zmin": {"type": "wall", "reflectance": [0.5, 0.4, 0.3], "emission": [0, 0, 1]},
                 "zmax": {"type": "open", "radiance": [0.1, 0.2, 0.3]}},
    "lights": [{"type": "directional", "direction": [0.3, -0.2, -1.0], "irradiance": [2.0, 1.5, 1.0]},
               {"type": "point", "position": [3.5, 3.5, 3.0], "intensity": [0.3, 0.2, 0.1]}]})
g_panel, g_scene = incident(panel), incident(scene)
check(len(g_panel) == 3 * 8 ** 3, f"RGB field on every voxel ({len(g_panel)} values)")
check(agree(g_panel, g_scene) < 1e-6,
      f"lights and faces from the panel = from the scene file (max rel. diff {agree(g_panel, g_scene):.1e})")
walls = panel.GetDataInformation(1).GetNumberOfCells()
check(walls == 8 * 8, f"the zmin wall's 8x8 patches on the Walls port ({walls})")

# 2. The material from ParaView's transfer functions (the Color Map Editor's
#    opacity function of RTData as the extinction) against the scene file's.
tf = pv.GetOpacityTransferFunction("RTData")
tf.Points = [EXTINCTION[0][0], EXTINCTION[0][1], 0.5, 0.0, EXTINCTION[1][0], EXTINCTION[1][1], 0.5, 0.0]
albedo = pv.CreatePiecewiseFunction(Points=[0.0, 0.8, 0.5, 0.0, 300.0, 0.8, 0.5, 0.0])
material = pv.VolumetricRadiosity(**common)
material.ExtinctionFunction = tf
material.AlbedoFunction = albedo
material.DirectionalLights = [0.3, -0.2, -1.0, 2.0, 1.5, 1.0]
by_file = pv.VolumetricRadiosity(**common)
by_file.SceneJSON = json.dumps({"version": 1, "material": {"extinction": EXTINCTION,
                                                           "albedo": [[0.0, 0.8]]}})
by_file.DirectionalLights = [0.3, -0.2, -1.0, 2.0, 1.5, 1.0]
g_tf, g_file = incident(material), incident(by_file)
check(agree(g_tf, g_file) < 1e-6,
      f"ParaView's transfer functions as the material = the scene file's (max rel. diff {agree(g_tf, g_file):.1e})")

# 3. A bad property is an error, not a silently wrong field.
bad = pv.VolumetricRadiosity(**common)
bad.MaterialPreset = "ct"
bad.Epsilon = 1e-3
bad.SceneJSON = "{ not json"
check(servermanager.Fetch(bad).GetPointData().GetArray("IncidentRadiation") is None,
      "malformed scene JSON: no field")

# 4. The lighting through a .vdb file: written with the plugin's writer
#    (SaveData picks it by the extension), read back with its reader.
vdb = os.path.join(tempfile.mkdtemp(), "lit.vdb")
pv.SaveData(vdb, proxy=panel)
read = pv.OpenDataFile(vdb)
check(read is not None and read.GetXMLName() == "OpenVDBGridReader",
      "OpenDataFile opens .vdb files with the plugin's reader")
if read is not None:
    read.GridName = "IncidentRadiation"
    back = servermanager.Fetch(read).GetPointData().GetArray("IncidentRadiation")
    values = [back.GetValue(i) for i in range(back.GetNumberOfValues())] if back else []
    check(agree(values, g_panel) < 1e-6,
          f"G written as a .vdb grid reads back the same ({len(values)} values)")

sys.exit(1 if failures else 0)
