#!/usr/bin/env python3
"""Compares a test image with a reference image, both linear RGB OpenEXR files of one size (for
example steadylight's path tracer against a Cycles render from scripts/cycles_reference.py), on
Rec. 709 luminance Y = 0.2126 R + 0.7152 G + 0.0722 B:

- per pixel: relative RMSE = sqrt(mean((Y_test - Y_ref)^2)) / mean(Y_ref);
- on block means: the same after averaging each image over BLOCK x BLOCK pixel blocks (default 4),
  which takes out most of the noise and the pixel filter, leaving bias;
- the ratio of mean luminances, mean(Y_test) / mean(Y_ref).

It reads the RGB channels of the default (unnamed) layer, which is where both steadylight and
Blender write the beauty image. Needs numpy and OpenImageIO's Python module (Debian:
python3-numpy python3-openimageio; run it with Debian's /usr/bin/python3).

Usage: compare_exr.py TEST.exr REFERENCE.exr [--block N]
"""
import argparse
import sys

import numpy as np
import OpenImageIO as oiio

REC709 = np.array([0.2126, 0.7152, 0.0722])


def read_luminance(path):
    """Rec. 709 luminance of the R, G and B channels of an EXR, as a float64 array (h, w)."""
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"{path}: {oiio.geterror()}")
    spec = image.spec()
    names = list(spec.channelnames)
    missing = [c for c in "RGB" if c not in names]
    if missing:
        sys.exit(f"{path}: no channel {', '.join(missing)} (channels: {', '.join(names)})")
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    rgb = np.stack([pixels[:, :, names.index(c)] for c in "RGB"], axis=-1).astype(np.float64)
    return rgb @ REC709


def block_means(y, block):
    """Means over block x block tiles; rows and columns that do not fill a tile are dropped."""
    h, w = (y.shape[0] // block) * block, (y.shape[1] // block) * block
    return y[:h, :w].reshape(h // block, block, w // block, block).mean(axis=(1, 3))


def relative_rmse(test, ref):
    return float(np.sqrt(np.mean((test - ref) ** 2)) / np.mean(ref))


def compare(test, ref, block):
    """The three figures of the module docstring, as a dict."""
    return {"rel_rmse_pixel": relative_rmse(test, ref),
            "rel_rmse_block": relative_rmse(block_means(test, block), block_means(ref, block)),
            "mean_ratio": float(test.mean() / ref.mean()),
            "mean_test": float(test.mean()), "mean_ref": float(ref.mean())}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("test")
    parser.add_argument("reference")
    parser.add_argument("--block", type=int, default=4, help="block size in pixels (default 4)")
    args = parser.parse_args()
    test, ref = read_luminance(args.test), read_luminance(args.reference)
    if test.shape != ref.shape:
        sys.exit(f"sizes differ: {test.shape[1]}x{test.shape[0]} vs {ref.shape[1]}x{ref.shape[0]}")
    r = compare(test, ref, args.block)
    print(f"mean luminance: test {r['mean_test']:.5f}, reference {r['mean_ref']:.5f}, "
          f"ratio {r['mean_ratio']:.4f}")
    print(f"relative RMSE of luminance: per pixel {r['rel_rmse_pixel']:.4f}, "
          f"{args.block}x{args.block} block means {r['rel_rmse_block']:.4f}")


if __name__ == "__main__":
    main()
