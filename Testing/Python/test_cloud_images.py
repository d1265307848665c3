"""Regression-image test of Examples/Python/cloud.py (ctest, labels python;rendering).

    xvfb-run -a /usr/bin/python3 Testing/Python/test_cloud_images.py \
        --output-dir OUT [--baseline-dir Testing/Baseline] [--threshold T] [--pixel-threshold P]
        [--compare-only] [--update-baselines] [-- EXAMPLE_ARGS...]

Runs the example (a procedural cloud under the sun and a blue sky) into OUT
and compares its two PNGs with the baselines of the same names; the
comparison, its tolerances (30 of 255 per channel, 2 pixels) and the
options are image_compare.py's, as for the CT head.

Measured on this machine (Mesa llvmpipe under Xvfb), as the thresholded
errors of the volume / slice pictures: two runs give identical pixels
(0 / 0). Turning the sun by 5 degrees about the vertical costs 0 / 0.28
(passes), by 10 degrees 0 / 70, lowering it by 10 degrees 0 / 726,
sending it from the other side (+x instead of -x) 1352 / 10332: the slice
of G on a log scale sees a 10-degree change of the sun, the volume
rendering (a smooth, soft medium, every pixel within the 30 of 255 per
channel) only large ones.
"""
import sys

from image_compare import main

NAMES = ("cloud_volume.png", "cloud_slice.png")

if __name__ == "__main__":
    sys.exit(main("cloud", NAMES, __doc__.split("\n")[0]))
