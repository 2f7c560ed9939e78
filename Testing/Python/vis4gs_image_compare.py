"""Masked image comparison for the baselines of views that show a selection.

A selection highlight or marker covers a few hundred pixels of a view; a whole-image
tolerance loose enough for renderer differences (Mesa versions, fonts) lets it vanish
unnoticed. So the image is compared in two regions:

- strictly inside a MASK around the highlights and markers: a pixel differs when a channel
  differs by more than STRICT_T (0-255), and at most STRICT_F of each mask's pixels may differ;
- loosely elsewhere: a pixel differs when a channel differs by more than LOOSE_T, and at
  most LOOSE_F of the other pixels may differ.

The mask is either a mask image (non-black pixels are strict) or computed, one mask per
highlight colour (--highlight=R,G,B, repeatable): every pixel of the baseline or of the test
image within COLOUR_T of that colour, grown by RADIUS pixels to take in the blended rim of a
splat or a line. Each mask holds to STRICT_F on its own, so that a 7x7 marker is not diluted
by a large highlighted frustum. Computing the masks from both images means a highlight
missing from the test and one drawn where the baseline has none are both compared strictly.

Usage: vis4gs_image_compare.py BASELINE.png TEST.png (--highlight=R,G,B... | --mask=M.png)
         [--colour-tolerance=40] [--radius=6] [--strict=24,0.02] [--loose=48,0.02]
         [--diff=DIFF.png] [--expect-mismatch]
Exit status 0 when the images match (with --expect-mismatch: when they do NOT match inside
the mask), 1 when they do not (prints "FAILED: ..."), 2 for unreadable input.
"""
import sys

import numpy as np


def read_png(path):
    """HxWx3 uint8, top row first."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader

    reader = vtkPNGReader()
    if not reader.CanReadFile(path):
        print(f"FAILED: {path} is missing or not a PNG file")
        sys.exit(2)
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)
    if pixels.shape[2] == 1:
        pixels = np.repeat(pixels, 3, axis=2)
    return np.ascontiguousarray(pixels[::-1, :, :3]).astype(np.uint8)


def write_png(path, pixels):
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter

    h, w = pixels.shape[:2]
    image = vtkImageData()
    image.SetDimensions(w, h, 1)
    flat = np.ascontiguousarray(pixels[::-1].reshape(h * w, -1))
    image.GetPointData().SetScalars(numpy_to_vtk(flat, deep=1))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def grow(mask, radius):
    """@p mask dilated by a (2 radius + 1)^2 square."""
    out = mask.copy()
    h, w = mask.shape
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            src = mask[max(0, -dy):h - max(0, dy), max(0, -dx):w - max(0, dx)]
            out[max(0, dy):h - max(0, -dy), max(0, dx):w - max(0, -dx)] |= src
    return out


def highlight_masks(images, colours, colour_tolerance, radius):
    """One mask per highlight colour: the pixels of any of @p images within
    @p colour_tolerance of it, grown by @p radius."""
    masks = []
    for colour in colours:
        near = np.zeros(images[0].shape[:2], dtype=bool)
        for image in images:
            distance = np.abs(image.astype(np.int16) - np.array(colour, dtype=np.int16))
            near |= distance.max(axis=2) <= colour_tolerance
        masks.append(grow(near, radius))
    return masks


def compare(baseline, test, masks, strict=(24, 0.02), loose=(48, 0.02)):
    """Each mask separately holds to @p strict (so a small marker is not diluted by a large
    highlighted frustum), the pixels of no mask to @p loose. Returns (ok, [(bad, pixels) per
    mask], (bad, pixels) outside, error image)."""
    error = np.abs(baseline.astype(np.int16) - test.astype(np.int16)).max(axis=2)
    inside = [(int((error[m] > strict[0]).sum()), int(m.sum())) for m in masks]
    outside = np.ones(error.shape, dtype=bool)
    for m in masks:
        outside &= ~m
    rest = (int((error[outside] > loose[0]).sum()), int(outside.sum()))
    ok = all(b <= strict[1] * n for b, n in inside) and rest[0] <= loose[1] * rest[1]
    return ok, inside, rest, error


def main(argv):
    files = [a for a in argv if not a.startswith("--")]
    options = {}
    colours = []
    for a in argv:
        if a.startswith("--"):
            key, _, value = a[2:].partition("=")
            if key == "highlight":
                colours.append(tuple(int(v) for v in value.split(",")))
            else:
                options[key] = value
    if len(files) != 2 or not (colours or "mask" in options):
        print(__doc__)
        return 2
    baseline, test = read_png(files[0]), read_png(files[1])
    if baseline.shape != test.shape:
        print(f"FAILED: {files[1]} is {test.shape[1]} x {test.shape[0]}, the baseline "
              f"{files[0]} {baseline.shape[1]} x {baseline.shape[0]}")
        return 1
    if "mask" in options:
        mask = read_png(options["mask"]).max(axis=2) > 0
        if mask.shape != baseline.shape[:2]:
            print(f"FAILED: the mask {options['mask']} is not the size of the baseline")
            return 2
        masks, names = [mask], [options["mask"]]
    else:
        masks = highlight_masks([baseline, test], colours,
                                int(options.get("colour-tolerance", 40)),
                                int(options.get("radius", 6)))
        names = ["highlight %d,%d,%d" % c for c in colours]
    for name, mask in zip(names, masks):
        if not mask.any():
            print(f"FAILED: the mask of {name} is empty in {files[0]} and {files[1]}")
            return 1
    strict = tuple(float(v) for v in options.get("strict", "24,0.02").split(","))
    loose = tuple(float(v) for v in options.get("loose", "48,0.02").split(","))
    ok, inside, rest, error = compare(baseline, test, masks, strict, loose)
    summary = (f"{files[1]} against {files[0]}: inside the mask of " + ", ".join(
        f"{name} {b} of {n} pixels" for name, (b, n) in zip(names, inside)) +
        f" differ by more than {strict[0]:g} (at most {strict[1]:g} allowed); outside "
        f"{rest[0]} of {rest[1]} by more than {loose[0]:g} (at most {loose[1]:g})")
    if "diff" in options:
        # Red: masked pixels that differ; grey: the error elsewhere; blue tint: the masks.
        diff = np.stack([error, error, error], axis=2).astype(np.uint8)
        for mask in masks:
            diff[mask, 2] = np.maximum(diff[mask, 2], 96)
            diff[mask & (error > strict[0])] = (255, 0, 0)
        write_png(options["diff"], diff)
    if "expect-mismatch" in options:
        # The mismatch must come from inside a mask: a different framing would fail too,
        # without proving that the highlight is what the comparison caught.
        caught = [name for name, (b, n) in zip(names, inside) if b > strict[1] * n]
        print((f"the comparison fails as it must ({', '.join(caught)}): " if caught
               else "FAILED: the missing highlight is not caught: ") + summary)
        return 0 if caught else 1
    print(("matches: " if ok else "FAILED: ") + summary)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
