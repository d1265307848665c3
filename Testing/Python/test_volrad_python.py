"""Tests the Python wrapping of VolRad::Filters (run by ctest, label python).

Builds an 8x8x8 emitting, absorbing, scattering cube in Python, lights it
with the dense solver and checks the output; then checks that a scene error
is reported as a VTK error and leaves no output. Exits non-zero on failure.
"""
import json
import math

from vtkmodules.vtkCommonCore import vtkCommand, vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

from volrad import vtkVolumetricRadiosity

N = 8


def make_volume():
    """An N^3 image with point arrays kappa_a, sigma_i, E_I (the default names)."""
    image = vtkImageData()
    image.SetDimensions(N, N, N)
    image.SetSpacing(0.1, 0.1, 0.1)
    # vtkFloatArray directly: Debian's python3 need not have numpy.
    arrays = {}
    for name in ("kappa_a", "sigma_i", "E_I"):
        a = vtkFloatArray()
        a.SetName(name)
        a.SetNumberOfTuples(N * N * N)
        image.GetPointData().AddArray(a)
        arrays[name] = a
    for k in range(N):
        for j in range(N):
            for i in range(N):
                p = i + N * (j + N * k)
                # Heterogeneous: denser towards +x, a hot core in the centre.
                arrays["kappa_a"].SetValue(p, 0.5 + i)
                arrays["sigma_i"].SetValue(p, 2.0)
                core = all(2 <= c < N - 2 for c in (i, j, k))
                arrays["E_I"].SetValue(p, 1.0 if core else 0.0)
    return image


def watch_errors(algorithm):
    """Collects the ErrorEvent messages (an observer also keeps them off stderr)."""
    messages = []

    @calldata_type(VTK_STRING)  # so that the message reaches Python
    def on_error(caller, event, message):
        messages.append(message)

    # The filter reports the cause; its executive reports the failed request.
    algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
    algorithm.GetExecutive().AddObserver(vtkCommand.ErrorEvent, on_error)
    return messages


def run(scene):
    f = vtkVolumetricRadiosity()
    errors = watch_errors(f)
    f.SetInputData(make_volume())
    f.SetSceneJSON(json.dumps(scene))
    f.Update()
    return f.GetOutput(), errors


# The dense solver: seconds at 8^3 (the hierarchical default takes longer).
scene = {
    "version": 1,
    "lights": [{"type": "directional", "direction": [0.3, 0.2, -1.0], "irradiance": 1.0}],
    "solver": {"method": "dense"},
}

# 1. A valid scene: G per point, finite and non-negative, energy conserved.
out, errors = run(scene)
assert not errors, errors
G = out.GetPointData().GetArray("IncidentRadiation")
assert G is not None, "no IncidentRadiation array"
assert G.GetNumberOfTuples() == out.GetNumberOfPoints() == N ** 3, G.GetNumberOfTuples()
assert G.GetNumberOfComponents() == 1, G.GetNumberOfComponents()
values = [G.GetValue(p) for p in range(G.GetNumberOfTuples())]
assert all(math.isfinite(g) and g >= 0.0 for g in values), "G not finite and >= 0"
assert max(values) > 0.0, "G is zero everywhere"
residual = out.GetFieldData().GetArray("EnergyBalanceResidual").GetComponent(0, 0)
assert residual < 1e-6, residual
method = out.GetFieldData().GetAbstractArray("SolverMethod").GetValue(0)
assert method == "dense", method
print(f"valid scene: G in [{min(values):.6g}, {max(values):.6g}], residual {residual:.3g}")

# 2. An unknown key is an error: reported, and no output arrays.
out, errors = run(dict(scene, unknown_key=1))
assert errors, "no ErrorEvent for an unknown scene key"
assert any("unknown_key" in m for m in errors), errors
assert out.GetPointData().GetArray("IncidentRadiation") is None, "output despite the error"
print(f"unknown key: {len(errors)} error(s), first: {errors[0].strip().splitlines()[-1]}")

print("test_volrad_python: OK")
