#!/usr/bin/env python3
"""Prints the 3x3 matrices of share/ocio/kiln.ocio, derived from the published primaries.

Rec.709 / sRGB: ITU-R BT.709 primaries, D65 white (0.3127, 0.3290).
ACES AP0 (ACES2065-1) and AP1 (ACEScg): SMPTE ST 2065-1 and S-2014-004, ACES white
(0.32168, 0.33767), which ACES calls D60.
Between the two whites the adaptation is Bradford's (von Kries in the Bradford cone space), as
the ACES reference transforms and OpenColorIO's *_BFD builtin transforms use.
The config's reference space is ACES2065-1, so each matrix is <space> -> AP0. Plain Python, no
NumPy: the machine this runs on need not have it.
"""

REC709 = ((0.64, 0.33), (0.30, 0.60), (0.15, 0.06), (0.3127, 0.3290))
AP1 = ((0.713, 0.293), (0.165, 0.830), (0.128, 0.044), (0.32168, 0.33767))
AP0 = ((0.7347, 0.2653), (0.0, 1.0), (0.0001, -0.0770), (0.32168, 0.33767))
BRADFORD = ((0.8951, 0.2664, -0.1614), (-0.7502, 1.7135, 0.0367), (0.0389, -0.0685, 1.0296))


def mul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def apply(m, v):
    return tuple(sum(m[i][k] * v[k] for k in range(3)) for i in range(3))


def inverse(m):
    (a, b, c), (d, e, f), (g, h, i) = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return ((( e * i - f * h) / det, -(b * i - c * h) / det, ( b * f - c * e) / det),
            (-(d * i - f * g) / det, ( a * i - c * g) / det, -(a * f - c * d) / det),
            (( d * h - e * g) / det, -(a * h - b * g) / det, ( a * e - b * d) / det))


def xyz(xy):
    x, y = xy
    return (x / y, 1.0, (1.0 - x - y) / y)


def xyz_from_rgb(space):
    """The RGB -> XYZ matrix whose white (1, 1, 1) is the space's white with Y = 1."""
    primaries = tuple(zip(*(xyz(p) for p in space[:3])))  # columns are the primaries' XYZ
    scale = apply(inverse(primaries), xyz(space[3]))
    return tuple(tuple(primaries[i][j] * scale[j] for j in range(3)) for i in range(3))


def bradford(source_white, target_white):
    s = apply(BRADFORD, xyz(source_white))
    t = apply(BRADFORD, xyz(target_white))
    scale = ((t[0] / s[0], 0, 0), (0, t[1] / s[1], 0), (0, 0, t[2] / s[2]))
    return mul(inverse(BRADFORD), mul(scale, BRADFORD))


def to_ap0(space):
    m = xyz_from_rgb(space)
    if space[3] != AP0[3]:
        m = mul(bradford(space[3], AP0[3]), m)
    return mul(inverse(xyz_from_rgb(AP0)), m)


def matrix_text(m):
    rows = [value for row in m for value in row]
    return "[" + ", ".join(f"{v:.17g}" for v in rows) + "]"


if __name__ == "__main__":
    print("Rec.709 -> AP0 (D65 -> D60, Bradford):", matrix_text(to_ap0(REC709)))
    print("AP1 -> AP0:", matrix_text(to_ap0(AP1)))
    print("Rec.709 -> AP1:", matrix_text(mul(inverse(to_ap0(AP1)), to_ap0(REC709))))
