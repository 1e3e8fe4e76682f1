"""What every kiln chart script shares: reading a CSV of measurements and saving a figure as PNG and
SVG. Needs matplotlib from Debian (python3-matplotlib, for /usr/bin/python3)."""
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    """The CSV file's rows as dicts keyed by its header."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, out, name):
    """Writes out/name.png and out/name.svg and closes the figure."""
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(out / f"{name}.{ext}", dpi=110)
    plt.close(fig)
    print(f"wrote {out / name}.png and .svg")
