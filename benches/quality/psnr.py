#!/usr/bin/env python3
"""Image quality of parallax renders: sRGB PSNR of a town frame's left image
against a converged plain path-traced reference of the same frame.

    python3 benches/quality/psnr.py --town town03 --frame 40 --weather clear \
        [--spp N] [--ref-spp 1024] [--size 320x180] [--bin target/release/parallax]
        [--cache DIR] [--extra "--no-filter"]

The reference is rendered once per (town, frame, weather, size, ref-spp, seed)
into the cache directory (plain path tracing: --no-filter, sensor noise off) and
reused. The test image is rendered with the binary's defaults (sensor noise off,
--baselines 10) plus --extra. Prints one JSON line: psnr_db, mean level error,
the bias of the mean light (mean_light_bias: linear display light, a share of
the reference's mean), the ratio of the two images' auto exposures, the scene
light's bias (the display light's with the exposures divided out), seconds, and
the reference's own noise estimate when two references exist
(--ref-pair renders a second reference with another sample seed: the PSNR
between the two is about 3 dB below each one's PSNR against the truth), and
with the pair, psnr_truth_db: the PSNR against the converged image, the
pair's noise subtracted from the squared error, and ref_psnr_truth_db, the
pair's mean's own.

With --light-lost, both the test image and a plain render of the same frame
at 4x its spp are also written as HDR, and light_lost is 1 - (the test's mean
scene radiance) / (the plain render's): the light the filters drop, free of
the exposure and the tone curve (a noisy reference's display mean sits below
its scene light, so the display-light bias above overstates a clean image's).
light_lost_by_class gives the same per semantic class of at least 5 % of the
pixels: the image's mean is mostly its brightest things (lamps, a car in the
head-lights), so a loss on the surfaces between them shows only there.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import time

import numpy as np
from PIL import Image


def load(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)


def psnr(a, b):
    mse = np.mean((a - b) ** 2)
    return float("inf") if mse == 0 else 10.0 * np.log10(255.0**2 / mse)


def linear(srgb):
    """8-bit sRGB levels to linear [0, 1] (the display image's light)."""
    c = srgb / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def render(binary, out, args):
    cmd = [binary, "render"] + args + ["-o", out]
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"render failed ({' '.join(cmd)}):\n{r.stderr}")
    return time.time() - t0


def left_png(out, frame):
    return os.path.join(out, "left", "rgb", f"{frame:06d}.png")


def exposure_scale(out, frame):
    """The frame's auto exposure, from the camera file of a render."""
    with open(os.path.join(out, "cameras", f"{frame:06d}.json")) as f:
        return json.load(f)["exposure_scale"]


def parser(description=None):
    """The frame, reference and binary arguments every quality script shares."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--town", default="town03")
    p.add_argument("--frame", type=int, default=40)
    p.add_argument("--weather", default="clear")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--size", default="320x180")
    p.add_argument("--spp", type=int, default=None, help="test spp (default: the binary's)")
    p.add_argument("--ref-spp", type=int, default=1024)
    p.add_argument("--ref-pair", action="store_true")
    p.add_argument("--bin", default="target/release/parallax")
    p.add_argument("--ref-bin", default=None, help="binary for the reference (default --bin)")
    p.add_argument("--cache", default="/work/refs")
    p.add_argument("--extra", default="", help="extra render arguments for the test image")
    p.add_argument("--out", default=None, help="keep the test render here")
    p.add_argument("--light-lost", action="store_true",
                   help="also measure the scene light lost against a plain HDR render")
    return p


def frame_args(a):
    """The render arguments of the frame both images show."""
    w, h = a.size.split("x")
    return ["--town", a.town, "--frame", str(a.frame), "--weather", a.weather,
            "--seed", str(a.seed), "--weather-seed", str(a.seed), "--width", w, "--height", h,
            "--baselines", "10", "--sensor-noise", "0"]


def references(a):
    """The reference images (one, or a pair with different sample seeds),
    rendered into the cache on first use, and the first one's directory."""
    key = f"{a.town}_f{a.frame}_{a.weather}_s{a.seed}_{a.size}_r{a.ref_spp}"
    refs = []
    for k, sample_seed in enumerate([1000 + a.seed, 2000 + a.seed][: 2 if a.ref_pair else 1]):
        d = os.path.join(a.cache, f"{key}_{k}")
        if not os.path.exists(left_png(d, a.frame)):
            render(a.ref_bin or a.bin, d + ".tmp", frame_args(a) + ["--spp", str(a.ref_spp), "--no-filter",
                                                 "--sample-seed", str(sample_seed)])
            os.rename(d + ".tmp", d)
        refs.append(load(left_png(d, a.frame)))
    return refs, os.path.join(a.cache, f"{key}_0")


def scores(img, refs):
    """PSNR and bias of `img` against the references' mean; with a pair,
    also against the converged image."""
    ref = refs[0] if len(refs) == 1 else (refs[0] + refs[1]) / 2
    res = {"psnr_db": round(psnr(img, ref), 2),
           "mean_abs_levels": round(float(np.mean(np.abs(img - ref))), 2),
           "bias_levels": round(float(np.mean(img - ref)), 3),
           # Light gained (+) or lost (-, e.g. fireflies dropped) as a share
           # of the reference's mean, in linear display light.
           "mean_light_bias": round(float(np.mean(linear(img)) / np.mean(linear(ref)) - 1.0), 4)}
    if len(refs) == 2:
        res["ref_pair_psnr_db"] = round(psnr(refs[0], refs[1]), 2)
        # The reference's own noise sets a floor under every clean image's
        # error: its variance (of the pair's mean, (r1 - r2)^2 / 4 per pixel,
        # unbiased for independent halves) subtracted from the squared
        # error leaves the error against the converged image.
        ref_var = np.mean((refs[0] - refs[1]) ** 2) / 4.0
        mse_truth = max(np.mean((img - ref) ** 2) - ref_var, 1e-9)
        res["psnr_truth_db"] = round(10.0 * np.log10(255.0**2 / mse_truth), 2)
        res["ref_psnr_truth_db"] = round(10.0 * np.log10(255.0**2 / ref_var), 2)
    return res


def hdr_luminance(out, frame):
    """Rec.709 luminance of a render's left HDR image (scene units), per pixel."""
    import OpenEXR
    import Imath
    f = OpenEXR.InputFile(os.path.join(out, "left", "rgb_hdr", f"{frame:06d}.exr"))
    px = Imath.PixelType(Imath.PixelType.FLOAT)
    r, g, b = (np.frombuffer(f.channel(c, px), np.float32).astype(np.float64) for c in "RGB")
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def semantic_classes(out, frame):
    """The left view's class id per pixel (flattened) and the class names."""
    ids = np.asarray(Image.open(os.path.join(out, "left", "semantic", f"{frame:06d}.png"))).ravel()
    with open(os.path.join(out, "cameras", f"{frame:06d}.json")) as f:
        names = {i: n for n, i in json.load(f)["semantic_classes"]}
    return ids, names


def light_lost(a, test_out):
    """1 - the test image's mean scene light over a plain render's at 4x its
    spp, over the image and per semantic class of at least 5 % of the
    pixels (the image's mean is mostly its brightest things: a loss on the
    surfaces between lamps hardly moves it)."""
    with open(os.path.join(test_out, "cameras", f"{a.frame:06d}.json")) as f:
        spp = json.load(f)["spp"]
    plain = test_out + "_plain"
    render(a.bin, plain, frame_args(a) + ["--hdr", "--no-filter", "--spp", str(4 * spp),
                                          "--sample-seed", str(3000 + a.seed)])
    test, ref = hdr_luminance(test_out, a.frame), hdr_luminance(plain, a.frame)
    ids, names = semantic_classes(test_out, a.frame)
    by_class = {}
    for c in np.unique(ids):
        k = ids == c
        if k.mean() >= 0.05 and ref[k].mean() > 0:
            by_class[names.get(int(c), str(c))] = round(1.0 - test[k].mean() / ref[k].mean(), 4)
    subprocess.run(["rm", "-rf", plain])
    return round(1.0 - test.mean() / ref.mean(), 4), by_class


def main():
    a = parser().parse_args()
    refs, ref_dir = references(a)
    out = a.out or f"/tmp/psnr_{os.getpid()}"
    extra = shlex.split(a.extra)
    common = frame_args(a)
    # Reference mode turns sensor noise off itself and refuses the flag.
    test_common = common[:-2] if "--reference" in extra else common
    args = test_common + (["--spp", str(a.spp)] if a.spp else []) + extra
    if a.light_lost:
        args.append("--hdr")
    secs = render(a.bin, out, args)
    img = load(left_png(out, a.frame))
    exposure = exposure_scale(out, a.frame) / exposure_scale(ref_dir, a.frame)
    res = {"town": a.town, "frame": a.frame, "weather": a.weather, "size": a.size,
           "spp": a.spp, "extra": a.extra}
    res.update(scores(img, refs))
    ref = refs[0] if len(refs) == 1 else (refs[0] + refs[1]) / 2
    # Auto exposure of the test image over the reference's: a noisy image
    # exposed differently is off everywhere, not only noisy. The scene
    # light's bias: the display light's with each image's exposure divided
    # out (exact where no pixel clips to white).
    res.update({"exposure_ratio": round(exposure, 4),
                "scene_light_bias": round(float(np.mean(linear(img)) / np.mean(linear(ref))
                                                / exposure - 1.0), 4),
                "seconds": round(secs, 2), "ref_spp": a.ref_spp * len(refs)})
    if a.light_lost:
        res["light_lost"], res["light_lost_by_class"] = light_lost(a, out)
    if not a.out:
        subprocess.run(["rm", "-rf", out])
    print(json.dumps(res))


if __name__ == "__main__":
    main()
