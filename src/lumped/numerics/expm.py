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


def expm(a: np.ndarray) -> np.ndarray:
    """``exp(a)`` of a square float array (module Notes)."""
    a = np.asarray(a, dtype=float)
    norm = float(np.abs(a).sum(axis=0).max(initial=0.0))  # the 1-norm
    if not math.isfinite(norm):
        raise ValueError("expm: the matrix has a non-finite entry")
    for m in (3, 5, 7, 9):
        if norm <= THETA[m]:
            return _pade(a, m)
    s = max(0, math.ceil(math.log2(norm / THETA[13])))
    r = _pade(a / 2.0**s, 13)
    for _ in range(s):
        r = r @ r
    return r
