"""Regression images of the Python examples: shared by test_ct_head_images.py,
test_frog_labels_images.py and test_cloud_images.py.

Each test runs its example (Examples/Python/NAME.py OUTDIR, which writes PNGs
at the baselines' size, 400x400) into --output-dir, unless --compare-only,
and compares each of its PNGs with the baseline of the same name the way
vtkRegressionTestImage does, with vtkImageDifference: per pixel, the
smallest colour difference over the pixel's 3x3 neighbours and 3x3 averages
(so that edges moved by a pixel or anti-aliased differently cost little),
minus a per-channel threshold; the thresholded error is the sum of what is
left over all pixels, in units of a fully wrong pixel. A picture whose error
passes the limit fails; its difference image (x10) is written next to it as
NAME.diff.png and the baseline as NAME.valid.png. The test exits non-zero
when any picture fails or is missing. --update-baselines copies the
pictures over the baselines (after a deliberate change; look at them first).

Defaults: 30 of 255 per channel free (--pixel-threshold) and at most 2
pixels' worth of error (--threshold); test_ct_head_images.py says why.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

from vtkmodules.vtkImagingCore import vtkImageDifference, vtkImageShiftScale
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "..")


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def write_png(image, path):
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def compare(test_path, baseline_path, threshold, pixel_threshold):
    """Returns (error, message); error None when the images cannot be compared."""
    if not os.path.isfile(baseline_path):
        return None, f"no baseline {baseline_path}"
    if not os.path.isfile(test_path):
        return None, f"the example wrote no {test_path}"
    test, baseline = read_png(test_path), read_png(baseline_path)
    if test.GetDimensions() != baseline.GetDimensions():
        return None, (f"size {test.GetDimensions()[:2]} differs from the baseline's "
                      f"{baseline.GetDimensions()[:2]}")
    diff = vtkImageDifference()
    diff.SetInputData(test)
    diff.SetImageData(baseline)
    diff.SetThreshold(pixel_threshold)
    diff.Update()
    error = diff.GetThresholdedError()
    if error > threshold:
        base = os.path.splitext(test_path)[0]
        # The difference image, amplified as VTK's own tests do.
        amplify = vtkImageShiftScale()
        amplify.SetInputConnection(diff.GetOutputPort())
        amplify.SetScale(10)
        amplify.ClampOverflowOn()
        amplify.SetOutputScalarTypeToUnsignedChar()
        amplify.Update()
        write_png(amplify.GetOutput(), base + ".diff.png")
        shutil.copyfile(baseline_path, base + ".valid.png")
        return error, (f"thresholded error {error:.3f} > {threshold:g}: see {base}.diff.png "
                       f"(test {test_path}, baseline copied to {base}.valid.png)")
    return error, f"thresholded error {error:.3f} <= {threshold:g}"


def main(example, names, description):
    """The command line of a regression-image test of Examples/Python/EXAMPLE.py
    whose pictures are `names`; returns the exit status."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--output-dir", required=True)
    parser.add_argument("--baseline-dir", default=os.path.join(SOURCE, "Testing", "Baseline"))
    parser.add_argument("--script", default=os.path.join(SOURCE, "Examples", "Python", example + ".py"))
    parser.add_argument("--threshold", type=float, default=2.0,
                        help="largest thresholded error, in fully wrong pixels (default 2)")
    parser.add_argument("--pixel-threshold", type=int, default=30,
                        help="colour difference per channel that costs nothing (default 30 of 255)")
    parser.add_argument("--compare-only", action="store_true",
                        help="compare the PNGs already in --output-dir")
    parser.add_argument("--update-baselines", action="store_true",
                        help="copy the pictures over the baselines instead of comparing")
    parser.add_argument("example_args", nargs="*",
                        help="after --: more arguments for the example (e.g. -- --light 1 0 0)")
    args = parser.parse_args()

    if not args.compare_only:
        # The example's default size (400x400) is the baselines' size.
        start = time.time()
        run = subprocess.run([sys.executable, args.script, args.output_dir] + args.example_args)
        print(f"{os.path.basename(args.script)}: exit {run.returncode}, {time.time() - start:.1f} s")
        if run.returncode != 0:
            return 1

    if args.update_baselines:
        os.makedirs(args.baseline_dir, exist_ok=True)
        for name in names:
            shutil.copyfile(os.path.join(args.output_dir, name), os.path.join(args.baseline_dir, name))
            print(f"updated {os.path.join(args.baseline_dir, name)}")
        return 0

    failed = 0
    for name in names:
        # No stale difference images from an earlier failure.
        for stale in (".diff.png", ".valid.png"):
            path = os.path.join(args.output_dir, os.path.splitext(name)[0] + stale)
            if os.path.exists(path):
                os.remove(path)
        error, message = compare(os.path.join(args.output_dir, name),
                                 os.path.join(args.baseline_dir, name), args.threshold,
                                 args.pixel_threshold)
        ok = error is not None and error <= args.threshold
        failed += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {message}")
        # For CDash, as vtkRegressionTestImage reports it.
        if error is not None:
            print(f'<DartMeasurement name="ImageError {name}" type="numeric/double">'
                  f"{error:.4f}</DartMeasurement>")
    return 1 if failed else 0
