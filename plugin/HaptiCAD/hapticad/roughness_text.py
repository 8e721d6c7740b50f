# SPDX-License-Identifier: GPL-3.0-or-later
"""A roughness category's band of real surfaces (seed 000, Table 2) as words: the one
text the panel, the overlay's legend and ``hapticad roughness-table`` show."""


def ra_band(row, ascii_only=False, grades=True):
    """"Ra 0.2–0.8 µm (N5, N6)" of a roughness-table row (``_core.roughness_category``).
    The open ends read "up to" and "over". ``ascii_only`` for Coin's text, which draws no
    µ or dash; ``grades`` False leaves the ISO N-grades out."""
    low, high = row.ra_min_um, row.ra_max_um
    micron, dash = ("um", "-") if ascii_only else ("µm", "–")
    if low is None and high is None:
        band = "Ra unclassified"
    elif low is None:
        band = f"Ra up to {high:g} {micron}"
    elif high is None:
        band = f"Ra over {low:g} {micron}"
    else:
        band = f"Ra {low:g}{dash}{high:g} {micron}"
    return band + (f" ({', '.join(row.n_grades)})" if grades and row.n_grades else "")
