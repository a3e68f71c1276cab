#!/usr/bin/env python3
"""Minimax coefficients of the batched sine and cosine of generated modules
(dynagen/src/codegen/sin_cos/kernel.rs), by the Remez exchange algorithm in
50-digit arithmetic (mpmath), rounded to the nearest double.

    pip install mpmath
    python3 scripts/sin_cos_minimax.py            # the coefficients (degree 5 and 5)
    python3 scripts/sin_cos_minimax.py 3 3        # other degrees (the f32 kernel's: 3 and 3)
    python3 scripts/sin_cos_minimax.py --table    # the bits of 2/pi of the slow path
    python3 scripts/sin_cos_minimax.py --references   # the huge-angle test values

On |r| <= pi/4, with z = r^2:

    sin r = r + r^3 * S(z)            S of degree NS (NS + 1 coefficients)
    cos r = 1 - z/2 + z^2 * C(z)      C of degree NC

Each polynomial minimises the largest error *relative to the function*
(sin r or cos r), the leading terms r and 1 - z/2 being exact. The script
prints the coefficients as Rust literals (the shortest text that reads back
as the same double) and the relative error bound of the rounded
polynomials, measured on a dense grid. Nothing in the build runs it: the
kernel carries the printed literals.
"""

import sys

import mpmath as mp

mp.mp.dps = 50


def remez(f, w, a, b, degree, iterations=30):
    """The polynomial p of `degree` minimising max |w(z) (p(z) - f(z))| on [a, b]."""
    n = degree + 2
    # Chebyshev extrema as the first reference.
    ref = [a + (b - a) * (1 - mp.cos(mp.pi * i / (n - 1))) / 2 for i in range(n)]
    grid = [a + (b - a) * (1 - mp.cos(mp.pi * i / 4000)) / 2 for i in range(4001)]
    coeffs = None
    for _ in range(iterations):
        # Solve w(z_i) (p(z_i) - f(z_i)) = (-1)^i E for the coefficients and E.
        m = mp.matrix(n, n)
        rhs = mp.matrix(n, 1)
        for i, z in enumerate(ref):
            for j in range(degree + 1):
                m[i, j] = z**j
            m[i, degree + 1] = (-1) ** i / w(z)
            rhs[i] = f(z)
        sol = mp.lu_solve(m, rhs)
        coeffs = [sol[j] for j in range(degree + 1)]

        def err(z):
            return w(z) * (mp.polyval(coeffs[::-1], z) - f(z))

        # New reference: the extremum of each run of one sign on the grid.
        values = [err(z) for z in grid]
        runs = []
        for z, e in zip(grid, values):
            if runs and mp.sign(e) == mp.sign(runs[-1][1]):
                if abs(e) > abs(runs[-1][1]):
                    runs[-1] = (z, e)
            else:
                runs.append((z, e))
        while len(runs) > n:
            # Drop the smaller end (the runs alternate in sign).
            if abs(runs[0][1]) < abs(runs[-1][1]):
                runs.pop(0)
            else:
                runs.pop()
        if len(runs) < n:
            break
        ref = [z for z, _ in runs]
    return coeffs


def shortest(x):
    """The shortest decimal text that reads back as the double x."""
    for digits in range(1, 18):
        s = f"{x:.{digits}e}"
        if float(s) == x:
            mant, exp = s.split("e")
            return f"{mant}e{int(exp)}"
    return repr(x)


def table():
    """2/pi as 20 64-bit limbs (1280 bits), most significant first."""
    with mp.workdps(450):
        v = int(mp.floor(2 / mp.pi * mp.mpf(2) ** 1280))
    limbs = [(v >> (64 * (19 - i))) & ((1 << 64) - 1) for i in range(20)]
    for i in range(0, 20, 4):
        print("        " + ", ".join(f"0x{l:016x}" for l in limbs[i : i + 4]) + ",")


def references():
    """sin and cos of a few large angles as double-doubles (hi, lo) (mpmath reduces exactly)."""
    xs = [1.6e6, 1.7e6, 3.0e7, 1e9, 123456789.0, 2.0**52, 2.5e15, 1e22, 1e100, 1e300,
          6381956970095103 * 2.0**797, 1.7976931348623157e308, -8.5e12]
    with mp.workdps(60):
        for x in xs:
            s, c = mp.sin(mp.mpf(x)), mp.cos(mp.mpf(x))
            sh, ch = float(s), float(c)
            print(f"({x!r}, ({sh!r}, {float(s - sh)!r}), ({ch!r}, {float(c - ch)!r})),")


def main():
    if sys.argv[1:] == ["--table"]:
        return table()
    if sys.argv[1:] == ["--references"]:
        return references()
    ns = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    nc = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    hi = (mp.pi / 4) ** 2
    lo = mp.mpf("1e-20")  # z = 0 itself: the functions below have a removable singularity there

    def f_sin(z):
        with mp.workdps(120):  # the difference cancels to a relative z
            r = mp.sqrt(z)
            return +((mp.sin(r) - r) / (r * z))

    def w_sin(z):  # error of r^3 S relative to sin r
        r = mp.sqrt(z)
        return r * z / mp.sin(r)

    def f_cos(z):
        with mp.workdps(120):  # the difference cancels to a relative z^2
            return +((mp.cos(mp.sqrt(z)) - 1 + z / 2) / (z * z))

    def w_cos(z):  # error of z^2 C relative to cos r
        return z * z / mp.cos(mp.sqrt(z))

    for name, f, w, degree in [("S", f_sin, w_sin, ns), ("C", f_cos, w_cos, nc)]:
        coeffs = remez(f, w, lo, hi, degree)
        rounded = [float(c) for c in coeffs]
        grid = [hi * i / 20000 for i in range(1, 20001)]
        worst = max(abs(w(z) * (mp.polyval([mp.mpf(c) for c in rounded[::-1]], z) - f(z))) for z in grid)
        print(f"// {name}: degree {degree} in z, max relative error {float(worst):.3e} (2^{float(mp.log(worst, 2)):.1f})")
        for i, c in enumerate(rounded):
            print(f"const {name}{i}: f64 = {shortest(c)};")


if __name__ == "__main__":
    main()
