#!/usr/bin/env python3
"""The top-level folders as floors: which folder includes which, and how many of those arrows run back up.

  folder_arrows.py ROOT [--at-most N]
      prints each arrow (folder -> folder, with one include that makes it), the floors from the top, and the count of
      arrows that run from a lower floor up to a higher one; exit 1 if more than N run back up

A floor order puts a folder above those it includes; where two folders include each other no order can, and the
order printed is the one with the fewest arrows running back up (all orders of the five folders are tried). The
includes are read as check_layers.py reads them (ARCHITECTURE.md, "Layers"): "swa/..." by the include/ folder that
holds it, anything else beside the including file; generated and system headers are no arrows. Tests are left out.
"""
import itertools
import os
import re
import sys

# The tree is walked and its includes matched as the layer check does it, one definition for both.
sys.dont_write_bytecode = True  # no __pycache__ left in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_layers import INCLUDE, TOPS, sources  # noqa: E402


def arrows(root):
    """{(from_top, to_top): 'file -> header'} for includes that cross top-level folders."""
    files = list(sources(root))
    headers = {}
    for rel in files:
        m = re.search(r"/include/(swa/.+\.h)$", rel)
        if m:
            headers.setdefault(m.group(1), rel)
    found = {}
    for rel in files:
        with open(os.path.join(root, rel), errors="replace") as f:
            for line in f:
                m = INCLUDE.match(line)
                if not m:
                    continue
                target = headers.get(m.group(1))
                if target is None:
                    beside = os.path.normpath(os.path.join(os.path.dirname(rel), m.group(1)))
                    target = beside if os.path.exists(os.path.join(root, beside)) else None
                if target is None:
                    continue
                pair = (rel.split("/")[0], target.split("/")[0])
                if pair[0] != pair[1]:
                    found.setdefault(pair, f"{rel} -> {target}")
    return found


def back_up(order, pairs):
    """The arrows that run up in `order` (top floor first)."""
    floor = {top: len(order) - i for i, top in enumerate(order)}
    return [p for p in pairs if floor[p[0]] < floor[p[1]]]


def main(root, at_most):
    found = arrows(root)
    best = min(itertools.permutations(TOPS), key=lambda order: (len(back_up(order, found)), order))
    up = back_up(best, found)
    for (a, b), example in sorted(found.items()):
        print(f"{a} -> {b}{'  (runs back up)' if (a, b) in up else ''}: {example}")
    print("floors from the top: " + ", ".join(best))
    print(f"folder_arrows: {len(found)} arrows, {len(up)} running back up")
    if at_most is not None and len(up) > at_most:
        print(f"folder_arrows: more than {at_most} arrow(s) run back up")
        return 1
    return 0


if __name__ == "__main__":
    args = sys.argv[1:]
    bar = None
    if len(args) == 3 and args[1] == "--at-most" and args[2].isdigit():
        bar = int(args[2])
        args = args[:1]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(args[0], bar))
