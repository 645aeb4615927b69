"""Cross-check of the transform against PyWavelets (Debian python3-pywt, run with
/usr/bin/python3), periodization mode: haar, bior2.2 (linear), bior3.3 (quadratic).

Normalisation: fogpipe's lifting is unnormalised (approximations are density-like), so
every PyWavelets coefficient is fogpipe's times sqrt(2) per level per dimension:
non-standard (wavedec2): band at depth k (1 = finest) and the approximation (depth J)
are 2^k times ours; standard (wavedec along x, then along y): a coefficient whose x
band has depth kx and y band depth ky is sqrt(2)^(kx+ky) times ours. Coefficient
positions agree with no shift in periodization mode (docs/platform.md: bior2.2 at
2^J n, haar and bior3.3 at 2^J n + (2^J-1)/2 -- the same as ours).

usage: pywt_compare.py DUMP_BINARY TMPDIR   (exit 77 = skipped: no pywt)"""
import os
import subprocess
import warnings
import sys

try:
    import numpy as np
    import pywt
except ImportError:
    print("pywt or numpy missing: skipped")
    sys.exit(77)

warnings.filterwarnings("ignore")  # "level too high" for small test sizes
dump, tmp = sys.argv[1], sys.argv[2]
names = {"haar": "haar", "linear": "bior2.2", "quadratic": "bior3.3"}
failures = 0
checks = 0


def lengths(n, J):
    return [n >> (J - l) for l in range(J + 1)]


def axis_scale(n, J):
    """sqrt(2)^depth for each coefficient index along one axis (standard layout)."""
    L = lengths(n, J)
    s = np.empty(n)
    s[: L[0]] = 2.0 ** (J / 2)
    for l in range(1, J + 1):
        s[L[l - 1]: L[l]] = 2.0 ** ((J - l + 1) / 2)
    return s


for basis, wname in names.items():
    for dec in ("nonstandard", "standard"):
        for (w, h, J) in ((64, 48, 3), (32, 32, 5), (40, 24, 2)):
            path = os.path.join(tmp, "pywt_%s_%s_%dx%d.bin" % (basis, dec, w, h))
            subprocess.run([dump, basis, dec, str(w), str(h), str(J), path], check=True)
            raw = np.fromfile(path, dtype=np.float32)
            os.remove(path)
            f = raw[: w * h].reshape(h, w)
            ours = raw[w * h:].reshape(h, w).astype(np.float64)
            if dec == "nonstandard":
                cs = pywt.wavedec2(f, wname, mode="periodization", level=J)
                ref = np.zeros((h, w))
                Lw, Lh = lengths(w, J), lengths(h, J)
                ref[: Lh[0], : Lw[0]] = cs[0] / 2.0 ** J
                for l in range(1, J + 1):
                    cH, cV, cD = cs[l]  # cH: high-pass along y; cV: along x
                    k = J - l + 1
                    ref[: Lh[l - 1], Lw[l - 1]: Lw[l]] = cV / 2.0 ** k
                    ref[Lh[l - 1]: Lh[l], : Lw[l - 1]] = cH / 2.0 ** k
                    ref[Lh[l - 1]: Lh[l], Lw[l - 1]: Lw[l]] = cD / 2.0 ** k
            else:
                rows = np.concatenate(pywt.wavedec(f.astype(np.float64), wname,
                                                   mode="periodization", level=J, axis=1), axis=1)
                full = np.concatenate(pywt.wavedec(rows, wname, mode="periodization",
                                                   level=J, axis=0), axis=0)
                ref = full / np.outer(axis_scale(h, J), axis_scale(w, J))
            err = np.max(np.abs(ref - ours)) / np.max(np.abs(f))
            checks += 1
            if not err <= 2e-6:
                failures += 1
                print("FAIL %s %s %dx%d J=%d: max relative difference %.3g"
                      % (basis, dec, w, h, J, err))
print("pywt_compare: %d checks, %d failed (pywt %s)" % (checks, failures, pywt.__version__))
sys.exit(1 if failures else 0)
