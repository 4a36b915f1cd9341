"""Write examples/ground_record.csv, the synthetic ground acceleration of examples/building.toml.

The record is *synthetic*: no earthquake was measured to make it.  It is a
sum of sines whose amplitudes follow the Kanai-Tajimi spectrum (H. Tajimi,
1960, the spectrum of ground acceleration filtered by a soil layer; firm
soil, ``omega_g = 15.6 rad/s``, ``zeta_g = 0.6``), with phases drawn
uniformly from a seeded random generator, multiplied by a trapezoidal
envelope of the Jennings-Housner-Tsai kind (a quadratic rise to 2 s, strong
motion to 10 s, exponential decay after, a half-cosine taper to exactly 0
over the last second), and scaled so that its peak is
3 m/s^2 (about 0.31 g).  It is a stand-in with the shape of strong motion
(a broad band around 2.5 Hz, a build-up and a decay), for an example that
runs as it is: use a measured record (written as ``t,a``) for design.

The frequencies are ``0.30, 0.35, ..., 10.25`` Hz (200 sines); the times
``0, 0.01, ..., 20`` s (2001 rows).  Values are written with 6 significant
digits, so the file is the same wherever NumPy's generator gives the same
phases (``numpy.random.default_rng(SEED)``, stable across NumPy versions).
``tests/test_examples.py`` checks that this script writes the committed file.

Examples::

    python scripts/ground_record.py                      # writes examples/ground_record.csv
    python scripts/ground_record.py --output record.csv  # elsewhere
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
OUTPUT = ROOT / "examples" / "ground_record.csv"

SEED = 20260121  #: of numpy.random.default_rng, for the phases
DT = 0.01  #: s, sampling interval
DURATION = 20.0  #: s
PEAK = 3.0  #: m/s^2, the record's largest |a|
FREQUENCIES = 0.30 + 0.05 * np.arange(200)  #: Hz
OMEGA_G, ZETA_G = 15.6, 0.6  #: rad/s and 1: Kanai-Tajimi's firm soil
RISE, STRONG_END, DECAY, TAPER = 2.0, 10.0, 0.5, 1.0  #: s, s, 1/s, s: the envelope


def kanai_tajimi(omega: np.ndarray) -> np.ndarray:
    """The Kanai-Tajimi spectral density at ``omega`` (rad/s), up to a constant factor."""
    g2, z2 = OMEGA_G**2, 4.0 * ZETA_G**2 * OMEGA_G**2
    return (g2 * g2 + z2 * omega**2) / ((g2 - omega**2) ** 2 + z2 * omega**2)


def envelope(t: np.ndarray) -> np.ndarray:
    """0 to 1: ``(t/RISE)^2`` up to ``RISE``, 1 up to ``STRONG_END``, then ``exp(-DECAY (t - STRONG_END))``,
    times a half cosine over the last ``TAPER`` seconds, so that the record ends at exactly 0 (a table
    load is 0 after its last time: no jump there)."""
    rise = np.minimum(t / RISE, 1.0) ** 2
    shape = np.where(t <= STRONG_END, rise, np.exp(-DECAY * (t - STRONG_END)))
    taper = 0.5 * (1.0 + np.cos(np.pi * np.clip((t - (DURATION - TAPER)) / TAPER, 0.0, 1.0)))
    return shape * taper


def record() -> tuple[np.ndarray, np.ndarray]:
    """Times (s) and ground accelerations (m/s^2) of the record, before rounding."""
    t = DT * np.arange(round(DURATION / DT) + 1)
    omega = 2.0 * np.pi * FREQUENCIES
    amplitude = np.sqrt(2.0 * kanai_tajimi(omega) * (2.0 * np.pi * 0.05))
    phase = np.random.default_rng(SEED).uniform(0.0, 2.0 * np.pi, FREQUENCIES.size)
    a = envelope(t) * (amplitude[None, :] * np.sin(np.outer(t, omega) + phase[None, :])).sum(axis=1)
    return t, PEAK * a / np.abs(a).max() + 0.0  # + 0.0: no -0 in the file


def text() -> str:
    """The CSV file: the provenance in ``#`` lines, the header ``t,a``, one row per sample."""
    t, a = record()
    header = [
        "# SYNTHETIC ground acceleration, not a measured earthquake: the load of examples/building.toml.",
        f"# Written by scripts/ground_record.py (seed {SEED}): 200 sines at 0.30-10.25 Hz with",
        f"# Kanai-Tajimi amplitudes (omega_g = {OMEGA_G} rad/s, zeta_g = {ZETA_G}) and random phases,",
        f"# times an envelope rising to {RISE:g} s, strong to {STRONG_END:g} s, decaying at {DECAY:g}/s after",
        f"# and tapered to 0 over the last {TAPER:g} s; scaled to a peak of {PEAK:g} m/s^2.",
        f"# t in s, a in m/s^2, every {DT:g} s for {DURATION:g} s.",
        "t,a",
    ]
    rows = [f"{ti:.2f},{ai:.6g}" for ti, ai in zip(t.tolist(), a.tolist())]
    return "\n".join(header + rows) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", type=Path, default=OUTPUT, help="the CSV file to write (default: %(default)s)")
    args = parser.parse_args()
    args.output.write_text(text(), encoding="utf-8")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
