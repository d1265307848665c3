"""Regression-image test of Examples/Python/smoke.py (ctest, labels python;rendering).

    xvfb-run -a /usr/bin/python3 Testing/Python/test_smoke_images.py \
        --output-dir OUT [--baseline-dir Testing/Baseline] [--threshold T] [--pixel-threshold P]
        [--compare-only] [--update-baselines] [-- EXAMPLE_ARGS...]

Runs the example (OpenVDB's smoke sample read with vtkOpenVDBGridReader,
solved at reduced resolution under the sun and a blue sky, the lighting
written back with vtkOpenVDBGridWriter) into OUT and compares its two PNGs
with the baselines of the same names; the comparison, its tolerances and
the options are image_compare.py's, as for the cloud.

Measured on this machine (Mesa llvmpipe under Xvfb), as the thresholded
errors of the volume / slice pictures: two runs give identical pixels
(0 / 0); the sun from the other side (--light -0.6 -0.7 -0.3) gives
1149 / 5001.
"""
import sys

from image_compare import main

NAMES = ("smoke_volume.png", "smoke_slice.png")

if __name__ == "__main__":
    sys.exit(main("smoke", NAMES, __doc__.split("\n")[0]))
