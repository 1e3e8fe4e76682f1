#!/usr/bin/python3
"""Horizontal bar charts of perf profiles (self time), one panel per report, side by side.

Input: text from `perf report --stdio --no-children --sort dso,sym -g none --percent-limit 0`.
Symbols of a library without a symbol table (Debian's Embree is stripped: perf shows bare
addresses) are summed into one bar per library, as are the kernel's and the dynamic loader's, so a
bar is a place the time goes rather than one address.

Bars: Embree red, kiln blue, other libraries, loader and kernel grey.

Usage: profile_bars.py OUT.png TITLE LABEL=REPORT.txt [LABEL=REPORT.txt ...] [--top N]
"""
import re
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

LINE = re.compile(r"^\s*([\d.]+)%\s+(\S+)\s+\[(.)\]\s+(.*?)\s*(?:-\s+-\s*)?$")


def short_symbol(sym):
    # C++ lambdas and templates make unreadable labels; keep the function's own name.
    sym = re.sub(r"\(anonymous namespace\)::", "", sym)
    sym = re.sub(r"\(kiln::scene const&.*$", "(...)::lambda", sym)
    return sym if len(sym) <= 48 else sym[:45] + "..."


def colour(label):
    """Embree red, kiln's own code blue, every other library and the kernel grey."""
    if label.startswith("libembree"):
        return "#c44e52"
    if label.startswith("kiln::") or label.startswith("std::"):
        return "#4c72b0"
    return "#8c8c8c"


def read_report(path):
    """{bar label: percent of samples}."""
    bars = defaultdict(float)
    for line in open(path, encoding="utf-8", errors="replace"):
        m = LINE.match(line)
        if not m:
            continue
        pct, dso, kind, sym = float(m.group(1)), m.group(2), m.group(3), m.group(4)
        lib = re.sub(r"\.so[.\d]*$", "", dso)
        if kind == "k":
            label = "[kernel] (all)"
        elif dso.startswith("ld-linux"):
            label = "dynamic loader ld.so (all)"
        elif sym.startswith("0x"):
            label = f"{lib} (stripped, all)"
        else:
            label = short_symbol(sym) if lib == "kiln" else f"{short_symbol(sym)} [{lib}]"
        bars[label] += pct
    return bars


def main(argv):
    top = 15
    if "--top" in argv:
        i = argv.index("--top")
        top = int(argv[i + 1])
        del argv[i : i + 2]
    out, title, runs = argv[1], argv[2], [a.split("=", 1) for a in argv[3:]]
    reports = [(label, read_report(path)) for label, path in runs]
    fig, axes = plt.subplots(1, len(reports), figsize=(7.5 * len(reports), 0.38 * top + 1.6))
    if len(reports) == 1:
        axes = [axes]
    xmax = max(max(r.values()) for _, r in reports) * 1.15
    for ax, (label, bars) in zip(axes, reports):
        items = sorted(bars.items(), key=lambda kv: -kv[1])[:top][::-1]
        names, values = [k for k, _ in items], [v for _, v in items]
        colors = [colour(n) for n in names]
        ax.barh(names, values, color=colors)
        for y, v in enumerate(values):
            ax.text(v + xmax * 0.01, y, f"{v:.1f}%", va="center", fontsize=8)
        ax.set_xlim(0, xmax)
        ax.set_xlabel("% of samples (self time)")
        ax.set_title(f"{label}: top {top} of {sum(bars.values()):.0f}% listed")
        ax.tick_params(axis="y", labelsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv)
