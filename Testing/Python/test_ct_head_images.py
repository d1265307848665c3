"""Regression-image test of Examples/Python/ct_head.py (ctest, labels python;rendering).

    xvfb-run -a /usr/bin/python3 Testing/Python/test_ct_head_images.py \
        --output-dir OUT [--baseline-dir Testing/Baseline] [--threshold T] [--pixel-threshold P]
        [--compare-only] [--update-baselines] [-- EXAMPLE_ARGS...]

Runs the example into OUT (unless --compare-only) and compares each of its
PNGs with the baseline of the same name the way vtkRegressionTestImage does,
with vtkImageDifference: per pixel, the smallest colour difference over the
pixel's 3x3 neighbours and 3x3 averages (so that edges moved by a pixel or
anti-aliased differently cost little), minus a per-channel threshold; the
thresholded error is the sum of what is left over all pixels, in units of a
fully wrong pixel. A picture whose error passes the limit fails; its
difference image (x10) is written next to it as NAME.diff.png and the
baseline as NAME.valid.png. Exits non-zero when any picture fails or is
missing. --update-baselines copies OUT's pictures over the baselines (after a
deliberate change; look at them first). The comparison and this command
line live in image_compare.py, shared with the other examples' image tests.

Tolerance. vtkImageDifference's default per-channel threshold (105 of 255)
is meant for geometry and lets smooth changes of shading through: turning
the light by 10 degrees passes it on the volume and bone pictures. Here the
per-channel threshold is 30 (--pixel-threshold) and the limit 2 pixels
(--threshold). Measured on this machine (Mesa llvmpipe under Xvfb), as the
thresholded errors of the volume / bone / slice pictures: two runs give
identical pixels (0 / 0 / 0); a 0.4% zoom with a 0.3 degree turn of the
camera (sub-pixel geometry) 0 / 0 / 0; 8x multisampling instead of none (a
far larger rasterisation change than Mesa versions make) 0 / 0.19 / 0.58.
Turning the light by 10 degrees about the vertical axis costs
7.9 / 25 / 1155, by 5 degrees 0.17 / 2.2 / 305, tilting it 10 degrees down
0.003 / 1.2 / 307: the slice of G on a log scale sees every change of the
light, the pictures of the geometry large ones.
"""
import sys

from image_compare import main

NAMES = ("ct_head_volume.png", "ct_head_bone.png", "ct_head_slice.png")

if __name__ == "__main__":
    sys.exit(main("ct_head", NAMES, __doc__.split("\n")[0]))
