"""Regression-image test of Examples/Python/frog_labels.py (ctest, labels python;rendering).

    xvfb-run -a /usr/bin/python3 Testing/Python/test_frog_labels_images.py \
        --output-dir OUT [--baseline-dir Testing/Baseline] [--threshold T] [--pixel-threshold P]
        [--compare-only] [--update-baselines] [-- EXAMPLE_ARGS...]

Runs the example (the frog's tissue labels lit through a label table) into
OUT and compares its two PNGs with the baselines of the same names; the
comparison, its tolerances (30 of 255 per channel, 2 pixels) and the
options are image_compare.py's, as for the CT head.

Measured on this machine (Mesa llvmpipe under Xvfb), as the thresholded
errors of the volume / slice pictures: two runs give identical pixels
(0 / 0). Turning the light by 5 degrees about the vertical costs
3.3 / 169, by 10 degrees 30 / 623, tilting it 10 degrees down 152 / 861,
sending it from the frog's other side (-y instead of +y) 2698 / 3805:
both pictures fail on each.
"""
import sys

from image_compare import main

NAMES = ("frog_labels_volume.png", "frog_labels_slice.png")

if __name__ == "__main__":
    sys.exit(main("frog_labels", NAMES, __doc__.split("\n")[0]))
