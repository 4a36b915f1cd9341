"""The matrix exponential of a small dense matrix, in NumPy: scaling and squaring with Padé approximants.

The exact solution of a network's phase is ``z(t) = expm(A t) z0``
(:mod:`lumped.solvers.network_phase`), taken thousands of times per run for
matrices of a few rows.  SciPy's ``scipy.linalg.expm`` computes the same to
the same accuracy, but calls the BLAS and LAPACK bundled with SciPy, whose
small calls slow down tenfold and more when other processes keep the cores
busy (measured: 8 us a 7 x 7 exponential alone, 60 to 160 us beside two busy
processes, 8 us again with ``OPENBLAS_NUM_THREADS=1``); NumPy's own
``matmul`` and ``solve`` do not.  So the package takes its exponentials here.

Notes
-----
Higham's algorithm (N. J. Higham, "The scaling and squaring method for the
matrix exponential revisited", SIAM J. Matrix Anal. Appl. 26 (2005)
1179-1193, Algorithm 2.3): with ``|A|_1 <= theta_m`` the diagonal Padé
approximant ``r_m(A) = (V - U)^-1 (V + U)`` of degree ``m`` in 3, 5, 7, 9 has
a backward error below the unit roundoff; otherwise ``A`` is scaled by
``2^-s`` into ``|A/2^s|_1 <= theta_13``, ``r_13`` taken and squared ``s``
times.  ``U`` holds the odd powers, ``V`` the even ones, with the
coefficients ``b_k`` of the approximant (Higham's Table 2.3 and eq. (2.1)).

Where that scaling is needed, Al-Mohy and Higham's bound through the norms of
powers (A. H. Al-Mohy, N. J. Higham, "A new scaling and squaring algorithm
for the matrix exponential", SIAM J. Matrix Anal. Appl. 31 (2009) 970-989,
Algorithm 5.1, the one SciPy's ``expm`` follows) is taken too, and the fewer
squarings of the two win: the approximant of degree ``m`` is as accurate
while ``alpha_p(A) = max(|A^p|^(1/p), |A^(p+1)|^(1/(p+1)))`` is below
:data:`THETA_POWERS` ``[m]``, and ``_ell`` adds the squarings that keep the
rounding of a matrix far from normal below the unit roundoff (their section 5).
Both bounds are valid, so either choice is backward stable; the 1-norm's is
kept wherever it does no worse, so those exponentials are unchanged to the bit.

Why the norms of powers: a phase's generator is far from normal (a stuck
phase's is nilpotent, ``[[0, 0], [T, 0]]``, with ``exp = I + A``).  Scaled by
its 1-norm, ``2^s ~ T`` squarings multiply the approximant's rounding by
``2^s`` (6e-2 absolute at ``T = 3e5``, 1e-9 relative at ``T = 9e7``; a belt at
1e-6 m/s run for 3e6 s ended 1 m off), while ``|A^p|^(1/p)`` is 0 for it: no
squaring, and ``r_3(A) = I + A`` to the rounding of one solve, for a phase of
any length.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["expm"]

#: Largest 1-norm for which the Padé approximant of each degree is used unscaled (Higham 2005, Table 2.3).
THETA = {
    3: 1.495585217958292e-2,
    5: 2.539398330063230e-1,
    7: 9.504178996162932e-1,
    9: 2.097847961257068,
    13: 5.371920351148152,
}

#: Largest ``alpha_p(A)`` for which each degree is used unscaled (Al-Mohy and Higham 2009, Table 3.1 and
#: section 5: ``theta_13 = 4.25``).
THETA_POWERS = {**THETA, 13: 4.25}

#: The coefficients b_0 .. b_m of the numerator of the degree-m diagonal Padé approximant of exp.
_B = {
    3: (120.0, 60.0, 12.0, 1.0),
    5: (30240.0, 15120.0, 3360.0, 420.0, 30.0, 1.0),
    7: (17297280.0, 8648640.0, 1995840.0, 277200.0, 25200.0, 1512.0, 56.0, 1.0),
    9: (17643225600.0, 8821612800.0, 2075673600.0, 302702400.0, 30270240.0, 2162160.0, 110880.0, 3960.0, 90.0, 1.0),
    13: (
        64764752532480000.0,
        32382376266240000.0,
        7771770303897600.0,
        1187353796428800.0,
        129060195264000.0,
        10559470521600.0,
        670442572800.0,
        33522128640.0,
        1323241920.0,
        40840800.0,
        960960.0,
        16380.0,
        182.0,
        1.0,
    ),
}


def _pade(a: np.ndarray, m: int) -> np.ndarray:
    """``r_m(A) = (V - U)^-1 (V + U)``."""
    b, eye = _B[m], np.eye(a.shape[0])
    a2 = a @ a
    if m == 13:
        a4 = a2 @ a2
        a6 = a4 @ a2
        u = a @ (a6 @ (b[13] * a6 + b[11] * a4 + b[9] * a2) + b[7] * a6 + b[5] * a4 + b[3] * a2 + b[1] * eye)
        v = a6 @ (b[12] * a6 + b[10] * a4 + b[8] * a2) + b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * eye
        return np.linalg.solve(v - u, v + u)
    odd, even, power = b[1] * eye, b[0] * eye, eye
    for k in range(1, m // 2 + 1):
        power = power @ a2
        odd, even = odd + b[2 * k + 1] * power, even + b[2 * k] * power
    u = a @ odd
    return np.linalg.solve(even - u, even + u)


def _norm1(a: np.ndarray) -> float:
    """The 1-norm (largest column sum of magnitudes)."""
    return float(np.abs(a).sum(axis=0).max(initial=0.0))


def _ell(a: np.ndarray, m: int) -> int:
    """Squarings to add so that the degree-``m`` approximant's rounding stays below the unit roundoff.

    ``alpha = |c_{2m+1}| | |A|^(2m+1) |_1 / |A|_1`` bounds the relative size of the series' leading error
    term; ``ceil(log2(alpha/u)/(2m))`` more halvings bring it below ``u = 2^-53`` (Al-Mohy and Higham 2009,
    eq. (5.1); ``1/|c_{2m+1}| = (2m)! (2m+1)!/(m!)^2``).  The norm of the power of the nonnegative ``|A|``
    is taken exactly, as a row of column sums carried through ``2m + 1`` products.
    """
    norm = _norm1(a)
    if norm == 0:
        return 0
    row = np.ones(a.shape[0])
    magnitudes = np.abs(a) / norm  # scaled by the norm, so no power overflows: |A|^p = norm^p |A/norm|^p
    for _ in range(2 * m + 1):
        row = row @ magnitudes
    power = float(row.max(initial=0.0))
    if power == 0:
        return 0
    reciprocal = math.comb(2 * m, m) * math.factorial(2 * m + 1)
    log2_alpha = math.log2(power) + 2 * m * math.log2(norm) - math.log2(reciprocal)  # norm^(2m+1) power / norm
    return max(0, math.ceil((log2_alpha + 53) / (2 * m)))


def _by_powers(a: np.ndarray) -> tuple[int, int] | None:
    """``(m, s)``: the degree and the squarings that Al-Mohy and Higham's bound through the norms of powers
    allows (module Notes); ``None`` where a power overflows (the 1-norm's choice then stands)."""
    with np.errstate(over="ignore", invalid="ignore"):
        a2 = a @ a
        a4 = a2 @ a2
        a6 = a4 @ a2
        a8 = a4 @ a4
        a10 = a4 @ a6
    d4, d6, d8, d10 = (_norm1(p) ** (1 / k) for p, k in ((a4, 4), (a6, 6), (a8, 8), (a10, 10)))
    if not math.isfinite(d10 + d8 + d6 + d4):
        return None
    eta = max(d4, d6)
    for m in (3, 5):
        if eta <= THETA_POWERS[m] and _ell(a, m) == 0:
            return m, 0
    eta = max(d6, d8)
    for m in (7, 9):
        if eta <= THETA_POWERS[m] and _ell(a, m) == 0:
            return m, 0
    eta = min(eta, max(d8, d10))
    s = max(0, math.ceil(math.log2(eta / THETA_POWERS[13]))) if eta > 0 else 0
    return 13, s + _ell(a / 2.0**s, 13)


def expm(a: np.ndarray) -> np.ndarray:
    """``exp(a)`` of a square float array (module Notes)."""
    a = np.asarray(a, dtype=float)
    norm = _norm1(a)
    if not math.isfinite(norm):
        raise ValueError("expm: the matrix has a non-finite entry")
    for m in (3, 5, 7, 9):
        if norm <= THETA[m]:
            return _pade(a, m)
    m, s = 13, max(0, math.ceil(math.log2(norm / THETA[13])))
    if s > 0 and (powers := _by_powers(a)) is not None:
        m, s = min((m, s), powers, key=lambda choice: (choice[1], choice[0]))
    r = _pade(a / 2.0**s, m)
    for _ in range(s):
        r = r @ r
    return r
