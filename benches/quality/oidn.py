#!/usr/bin/env python3
"""What Intel Open Image Denoise would give: a town frame rendered as plain
path tracing at the binary's default spp (`--no-filter --hdr`: linear
radiance plus the left view's first-surface albedo and normal), the left
image denoised by OIDN (PyPI `pyoidn`, CPU) and put through the binary's
own display transform, scored against the same references as psnr.py.

    pip install pyoidn OpenEXR
    python3 benches/quality/oidn.py --town town10 --frame 40 --weather clear \
        --ref-spp 256 --ref-pair [--input plain|default] [--aux none|albedo_normal]

Prints one JSON line: the scores (psnr.py's) of the binary's own image and
of the OIDN image, and OIDN's seconds. `--input default` denoises the
binary's default (filtered) render instead. This is a measurement only:
the renderer does not call OIDN.
"""
import json
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import psnr  # noqa: E402  (the sibling script: references and scores)


def read_exr(path):
    """An EXR's three channels (RGB or XYZ) as an H × W × 3 float32 array."""
    import Imath
    import OpenEXR

    f = OpenEXR.InputFile(path)
    dw = f.header()["dataWindow"]
    w, h = dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1
    names = list(f.header()["channels"].keys())
    chans = next(c for c in (["R", "G", "B"], ["X", "Y", "Z"]) if set(c) <= set(names))
    pt = Imath.PixelType(Imath.PixelType.FLOAT)
    return np.stack([np.frombuffer(f.channel(c, pt), np.float32).reshape(h, w) for c in chans], -1)


def display(hdr, exposure):
    """The binary's display transform (film/tone.rs): exposure, the ACES fit
    per channel, the sRGB curve, 8-bit levels."""
    x = np.nan_to_num(hdr * exposure, nan=0.0, posinf=8.0)
    x = np.maximum(x, 0.0)
    y = np.where(x >= 8.0, 1.0, np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0, 1))
    s = np.where(y <= 0.0031308, 12.92 * y, 1.055 * np.power(y, 1 / 2.4) - 0.055)
    return np.round(np.clip(s, 0, 1) * 255.0)


def left_map(out, name, frame):
    return read_exr(os.path.join(out, "left", name, f"{frame:06d}.exr"))


def main():
    p = psnr.parser(__doc__.splitlines()[0])
    p.add_argument("--input", choices=["plain", "default"], default="plain")
    p.add_argument("--aux", choices=["none", "albedo_normal"], default="albedo_normal")
    p.add_argument("--quality", default="high")
    a = p.parse_args()
    import pyoidn

    refs, _ = psnr.references(a)
    out = a.out or f"/tmp/oidn_{os.getpid()}"
    args = psnr.frame_args(a) + (["--spp", str(a.spp)] if a.spp else []) + ["--hdr"]
    if a.input == "plain":
        args.append("--no-filter")
    secs = psnr.render(a.bin, out, args)
    exposure = psnr.exposure_scale(out, a.frame)
    hdr = left_map(out, "rgb_hdr", a.frame)
    aux = {}
    if a.aux == "albedo_normal":
        # Averaged over each pixel's samples: noise-free apart from edges.
        aux = dict(albedo=np.clip(left_map(out, "albedo", a.frame), 0, 1),
                   normal=np.clip(left_map(out, "aov_normal", a.frame), -1, 1), clean_aux=True)
    t0 = time.time()
    # Denoised as displayed light (exposure applied), as OIDN expects HDR
    # values around 1.
    den = pyoidn.denoise(np.ascontiguousarray(hdr * exposure, dtype=np.float32), hdr=True,
                         quality=a.quality, **aux)
    oidn_secs = time.time() - t0
    img = display(den, 1.0)
    own = psnr.load(psnr.left_png(out, a.frame))
    res = {"town": a.town, "frame": a.frame, "weather": a.weather, "size": a.size,
           "input": a.input, "aux": a.aux,
           "own": psnr.scores(own, refs), "oidn": psnr.scores(img, refs),
           "render_seconds": round(secs, 2), "oidn_seconds": round(oidn_secs, 2),
           # The transform's match to the binary's own PNG (rounding only).
           "display_max_diff": float(np.abs(display(hdr, exposure) - own).max())}
    if not a.out:
        subprocess.run(["rm", "-rf", out])
    print(json.dumps(res))


if __name__ == "__main__":
    main()
