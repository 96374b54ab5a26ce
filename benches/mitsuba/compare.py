#!/usr/bin/env python3
"""parallax against Mitsuba 3 on shared scenes (issue 23 items 5 and 6).

For each scene of benches/mitsuba/scenes/ (sunlit diffuse + GGX, night point
and spot lights, homogeneous fog):

1. Agreement: `parallax render --reference` and Mitsuba 3 (the scene written
   by `parallax export --mitsuba`, max_depth D+1) at high spp; per-channel
   image means (target: within 1 %) and a structured-difference check: the
   difference image averaged over BxB blocks, in units of its own noise
   (estimated from two independent half-spp renders of each), should be
   unit-variance noise: mean z^2 near 1, no block beyond |z| > 5.
2. Equal time: parallax default, parallax --reference and Mitsuba 3 (LLVM,
   `multijitter` and `ldsampler` samplers) each given the same wall time on THREADS threads; RMSE of
   the linear left image against a shared reference (the mean of both
   high-spp renders of step 1), and parallax default's RMSE / Mitsuba's.

Usage: python3 benches/mitsuba/compare.py [--small] [--parallax BIN]
       [--scenes sunlit,night,fog] [--out DIR] [--spp N] [--seconds S]
--small (CI): 80x45, 2 x 128 spp, Mitsuba scalar_rgb (no JIT compile), the
agreement only (equal time needs the LLVM variant).
Needs `pip install mitsuba numpy`; the LLVM variant needs libLLVM >= 15
with fminimum support (Debian 12: `apt-get install libllvm19`; found
automatically, or set DRJIT_LIBLLVM_PATH), else it falls back to scalar_rgb.
"""

import argparse
import glob
import json
import os
import re
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SCENES = ["sunlit", "night", "fog"]
# Mitsuba 3's low-discrepancy samplers (it has no `sobol`; `ldsampler` is
# its Sobol-based (0,2)-sequence sampler).
MITSUBA_SAMPLERS = ("multijitter", "ldsampler")


def find_llvm():
    """A libLLVM Dr.Jit's LLVM backend can use (Debian 12's 15 and 16 lack
    x86 fminimum); None to let Dr.Jit search."""
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return os.environ["DRJIT_LIBLLVM_PATH"]
    for v in range(30, 16, -1):
        for p in glob.glob(f"/usr/lib/*/libLLVM-{v}.so") + glob.glob(f"/usr/lib/llvm-{v}/lib/libLLVM*.so"):
            return p
    return None


def mitsuba_variant(threads, variants):
    llvm = find_llvm()
    if llvm:
        os.environ["DRJIT_LIBLLVM_PATH"] = llvm
    import drjit as dr
    import mitsuba as mi
    for variant in variants:
        try:
            mi.set_variant(variant)
            if variant.startswith("llvm"):
                # A tiny render proves the JIT works (it aborts on bad LLVMs).
                probe = subprocess.run(
                    [sys.executable, "-c",
                     "import mitsuba as mi; mi.set_variant('llvm_ad_rgb'); "
                     "mi.render(mi.load_dict(mi.cornell_box()), spp=1)"],
                    capture_output=True, timeout=600)
                if probe.returncode != 0:
                    raise RuntimeError("LLVM backend does not compile here")
            break
        except Exception as e:  # noqa: BLE001 - any failure: next variant
            print(f"mitsuba {variant} unavailable: {e}", file=sys.stderr)
    dr.set_thread_count(threads)
    return mi, dr, mi.variant()


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {p.returncode}\n{p.stdout}{p.stderr}")
    return p.stdout + p.stderr


def parallax_render(args, scene, out, spp, seed, reference, threads):
    """Linear left image and path-pass seconds per view of one render."""
    cmd = [args.parallax, "render", scene, "-o", out, "--spp", str(spp),
           "--seed", str(seed), "--threads", str(threads), "--hdr",
           "--baselines", "54"]
    if reference:
        cmd.append("--reference")
    text = run(cmd)
    m = re.search(r"path ([0-9.]+) s", text)
    path_s = float(m.group(1)) / 2.0 if m else float("nan")  # two views
    return read_exr(os.path.join(out, "left", "rgb_hdr", "000000.exr")), path_s


def read_exr(path):
    import mitsuba as mi
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


class MitsubaScene:
    """An exported scene loaded once per sampler and spp; renders reuse
    Dr.Jit's compiled kernels (the first render of a size compiles)."""

    def __init__(self, mi, xml):
        self.mi, self.xml, self.loaded = mi, xml, {}

    def render(self, spp, seed, sampler="independent"):
        """Linear image, seconds of `mi.render` and the spp taken
        (multijitter rounds spp up to a product of two near factors)."""
        key = (spp, sampler)
        if key not in self.loaded:
            self.loaded[key] = self.mi.load_file(self.xml, spp=spp, sampler=sampler)
        scene = self.loaded[key]
        taken = scene.sensors()[0].sampler().sample_count()
        t = time.time()
        img = np.array(self.mi.render(scene, seed=seed), dtype=np.float64)[..., :3]
        return img, time.time() - t, taken


def block_mean(img, b):
    h, w = img.shape[0] // b * b, img.shape[1] // b * b
    x = img[:h, :w].reshape(h // b, b, w // b, b, -1)
    return x.mean(axis=(1, 3))


def agreement(p1, p2, m1, m2, block):
    """Per-channel relative mean difference, and the difference image's BxB
    block means in units of their own noise: the variance of p - m per pixel
    is estimated without bias by ((p1 - p2)/2)^2 + ((m1 - m2)/2)^2 from the
    independent halves, so unbiased renderers give z ~ N(0, 1) per block."""
    p, m = (p1 + p2) / 2, (m1 + m2) / 2
    rel = (p.mean(axis=(0, 1)) - m.mean(axis=(0, 1))) / m.mean(axis=(0, 1))
    var = ((p1 - p2) / 2) ** 2 + ((m1 - m2) / 2) ** 2
    # Standard error of the relative mean difference (per channel).
    rel_se = np.sqrt(var.sum(axis=(0, 1))) / var[..., 0].size / m.mean(axis=(0, 1))
    sigma = np.sqrt(block_mean(var, block) / block ** 2)
    z = block_mean(p - m, block) / np.maximum(sigma, 1e-12)
    # Blocks without noise (empty sky, black night) carry no information.
    live = sigma > 1e-9 * max(float(np.abs(p).mean()), 1e-12)
    z = z[live]
    return {
        "mean_rel_diff": rel.tolist(),
        "mean_rel_se": rel_se.tolist(),
        "mean_z2": float((z ** 2).mean()),
        "max_abs_z": float(np.abs(z).max()),
        "blocks_over_5": float((np.abs(z) > 5).mean()),
        "blocks": int(z.size),
    }


def rmse(a, b):
    return float(np.sqrt(((a - b) ** 2).mean()))


def rmse_to_truth(img, ref, ref_var):
    """RMSE of `img` against the converged image: its mean squared error
    against `ref` less the reference's own noise (an independent render's
    error adds its variance `ref_var` to the expected squared error)."""
    mse = float(((img - ref) ** 2).mean()) - float(ref_var.mean())
    return float(np.sqrt(max(mse, 0.0)))


def at_budget(render, spp, seconds, round_spp=lambda n: n):
    """Renders with `render(spp) -> (img, seconds, spp taken)` at the spp
    that takes `seconds`: scaled from a first run, corrected once more when
    the result is off by over 15 % (costs are not quite linear in spp)."""
    img, t, taken = render(spp)
    for _ in range(3):
        if abs(t / seconds - 1) <= 0.15:
            break
        spp = max(1, round_spp(int(taken * seconds / max(t, 1e-3))))
        img, t, taken = render(spp)
    return img, t, taken


def equal_time(args, ms, scene, work, ref, ref_var, seconds, threads, samplers):
    """RMSE against `ref` of each renderer given `seconds` of wall time, and
    against the truth (`rmse_to_truth`, the reference's variance `ref_var`
    taken out): fireflies left in the reference otherwise set a floor that
    hides the difference between clean images."""
    def scores(img):
        return {"rmse": rmse(img, ref), "rmse_truth": rmse_to_truth(img, ref, ref_var)}

    res = {}
    for mode in ("default", "reference"):
        out = os.path.join(work, f"et_{mode}")

        def render(spp, mode=mode, out=out):
            img, t = parallax_render(args, scene, out, spp, 8, mode == "reference", threads)
            return img, t, spp

        img, t, spp = at_budget(render, 4, seconds)
        res[f"parallax_{mode}"] = {"spp": spp, "seconds": t, **scores(img)}
    for sampler in samplers:
        # A power of 4 for ldsampler (it rounds up otherwise).
        round_spp = (lambda n: 4 ** max(1, int(np.log(n) / np.log(4)))) if sampler == "ldsampler" else (lambda n: n)

        def render(spp, sampler=sampler):
            ms.render(spp, 9, sampler)  # compiles at this size
            return ms.render(spp, 10, sampler)

        img, t, taken = at_budget(render, 16, seconds, round_spp)
        res[f"mitsuba_{sampler}"] = {"spp": taken, "seconds": t, **scores(img)}
    for key, name in (("rmse", "default_over_mitsuba"), ("rmse_truth", "default_over_mitsuba_truth")):
        best = min(res[f"mitsuba_{s}"][key] for s in samplers)
        res[name] = res["parallax_default"][key] / max(best, 1e-12)
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--parallax", default=os.path.join(REPO, "target", "release", "parallax"))
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--out", default="/tmp/parallax-mitsuba")
    ap.add_argument("--spp", type=int, default=1024, help="agreement spp per half (x2 in all)")
    ap.add_argument("--seconds", type=float, default=20.0, help="equal-time budget per render")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--block", type=int, default=8, help="block size of the structured check")
    ap.add_argument("--small", action="store_true",
                    help="CI mode: 80x45, 2 x 128 spp, Mitsuba scalar_rgb (no JIT), agreement only")
    ap.add_argument("--json", help="write the results here")
    args = ap.parse_args()
    variants = ("scalar_rgb",) if args.small else ("llvm_ad_rgb", "scalar_rgb")
    mi, _, variant = mitsuba_variant(args.threads, variants)
    width, height = (80, 45) if args.small else (None, None)
    if args.small:
        args.spp, args.block = 128, 5
    print(f"mitsuba {mi.__version__} variant {variant}, {args.threads} threads, "
          f"{args.spp} spp x 2 per renderer")
    results = {}
    failed = False
    for name in args.scenes.split(","):
        src = os.path.join(HERE, "scenes", f"{name}.toml")
        work = os.path.join(args.out, name)
        os.makedirs(work, exist_ok=True)
        scene = src
        if width:
            # A copy at the small size (parallax reads the size from the file).
            text = open(src).read()
            text = re.sub(r"^width = \d+", f"width = {width}", text, flags=re.M)
            text = re.sub(r"^height = \d+", f"height = {height}", text, flags=re.M)
            scene = os.path.join(work, f"{name}.toml")
            open(scene, "w").write(text)
        xml_dir = os.path.join(work, "mitsuba")
        if os.path.isdir(xml_dir):
            subprocess.run(["rm", "-rf", xml_dir])
        run([args.parallax, "export", "--mitsuba", scene, "-o", xml_dir])
        xml = os.path.join(xml_dir, "scene.xml")
        p1, _ = parallax_render(args, scene, os.path.join(work, "p1"), args.spp, 101, True, args.threads)
        p2, _ = parallax_render(args, scene, os.path.join(work, "p2"), args.spp, 202, True, args.threads)
        ms = MitsubaScene(mi, xml)
        m1 = ms.render(args.spp, 101)[0]
        m2 = ms.render(args.spp, 202)[0]
        agree = agreement(p1, p2, m1, m2, args.block)
        ref = (p1 + p2 + m1 + m2) / 4
        # Unbiased per-pixel variance of `ref` from the halves' differences:
        # Var(mean of 4) = (Var p + Var m) / 8, Var p = E[(p1 - p2)^2] / 2.
        ref_var = ((p1 - p2) ** 2 + (m1 - m2) ** 2) / 16
        # Equal time needs the LLVM variant (scalar Mitsuba is not its speed).
        et = None
        if variant.startswith("llvm"):
            et = equal_time(args, ms, scene, work, ref, ref_var, args.seconds, args.threads, MITSUBA_SAMPLERS)
        results[name] = {"agreement": agree, "equal_time": et}
        # Within 1 %, or within 4 standard errors (low spp: fireflies).
        ok_mean = all(abs(r) <= max(0.01, 4 * e)
                      for r, e in zip(agree["mean_rel_diff"], agree["mean_rel_se"]))
        ok_struct = agree["blocks_over_5"] <= 0.01
        failed |= not (ok_mean and ok_struct)
        rel = ", ".join(f"{100 * r:+.3f} ± {100 * e:.3f} %"
                        for r, e in zip(agree["mean_rel_diff"], agree["mean_rel_se"]))
        print(f"{name}: mean diff (R, G, B) {rel} [{'ok' if ok_mean else 'OVER 1 % and 4 s.e.'}]; "
              f"{agree['blocks']} blocks: mean z^2 {agree['mean_z2']:.2f} (noise: 1), "
              f"max |z| {agree['max_abs_z']:.1f}, {100 * agree['blocks_over_5']:.2f} % over 5 "
              f"[{'ok' if ok_struct else 'STRUCTURED'}]")
        for k, v in (et or {}).items():
            if isinstance(v, dict):
                print(f"  {k:20s} {v['spp']:6d} spp {v['seconds']:7.2f} s  RMSE {v['rmse']:.5f}"
                      f"  (to the truth {v['rmse_truth']:.5f})")
        if et:
            print(f"  parallax default RMSE / Mitsuba's best: {et['default_over_mitsuba']:.2f}"
                  f" (to the truth: {et['default_over_mitsuba_truth']:.2f}; reference noise"
                  f" RMS {float(np.sqrt(ref_var.mean())):.5f})")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
