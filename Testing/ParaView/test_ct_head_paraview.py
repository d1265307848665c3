"""Regression image of the ParaView workflow (Examples/ParaView/ct_head.py).

    xvfb-run -a pvpython --force-offscreen-rendering test_ct_head_paraview.py \
        --output-dir DIR [--plugin VolRad.so] [--update-baselines]

Runs the example's pipeline in this pvpython (plugin loaded, CT head read,
lit by the Volumetric Radiosity filter, volume-rendered off-screen), saves
DIR/paraview_ct_head.png and compares it with
Testing/Baseline/paraview_ct_head.png by Testing/Python/image_compare.py's
rule (vtkImageDifference, 30 of 255 per channel free, at most 2 pixels'
worth of error); a failure leaves .diff.png and .valid.png next to it.
"""
import argparse
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "..")
sys.path[:0] = [os.path.join(SOURCE, "Examples", "ParaView"), os.path.join(SOURCE, "Testing", "Python")]
import ct_head  # noqa: E402
import image_compare  # noqa: E402

NAME = "paraview_ct_head.png"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output-dir", required=True)
    parser.add_argument("--baseline-dir", default=os.path.join(SOURCE, "Testing", "Baseline"))
    parser.add_argument("--plugin", help="the VolRad plugin (VolRad.so)")
    parser.add_argument("--threshold", type=float, default=2.0)
    parser.add_argument("--pixel-threshold", type=int, default=30)
    parser.add_argument("--update-baselines", action="store_true")
    args = parser.parse_args()

    picture = ct_head.save_picture(args.output_dir, plugin=args.plugin)
    baseline = os.path.join(args.baseline_dir, NAME)
    if args.update_baselines:
        shutil.copyfile(picture, baseline)
        print(f"updated {baseline}")
        return 0
    # The view is done with: closed before the comparison's own VTK objects,
    # so that the X connection is not torn down under a live render window.
    import paraview.simple
    paraview.simple.Delete(paraview.simple.GetActiveView())
    error, message = image_compare.compare(picture, baseline, args.threshold, args.pixel_threshold)
    ok = error is not None and error <= args.threshold
    print(f"{'ok  ' if ok else 'FAIL'} {NAME}: {message}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
