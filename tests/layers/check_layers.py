#!/usr/bin/env python3
"""The floor plan's layers (ARCHITECTURE.md, "Layers"), enforced: every #include "..." of a source file under agent/,
sim/, monitor/, idl/ or deploy/ must name a header of its own layer or a lower one. A file in no layer is an error too,
so a new folder has to be given its place.

  check_layers.py ROOT        exit 0: every include follows the order; 1: one line per include against it
"""
import os
import re
import sys

# Low to high. A layer may include its own and lower layers only. Paths are folders or single files, relative to the
# source tree; the longest match decides.
LAYERS = [
    ("foundation", ["agent/params", "idl/msg_defs", "idl/runtime/app/cli.cpp", "idl/runtime/app/help_format.cpp",
                    "idl/runtime/app/help_format.h", "idl/runtime/app/number.cpp",
                    "idl/runtime/app/include/swa/app/cli.h", "idl/runtime/app/include/swa/app/number.h"]),
    ("agent core", ["agent/include", "agent/src", "agent/config", "agent/px4", "agent/autopilot"]),
    ("sim core", ["sim/include", "sim/src", "sim/scenario"]),
    ("monitor core", ["monitor/include", "monitor/src", "monitor/svg", "monitor/run_record", "monitor/recording"]),
    ("wire", ["idl"]),
    ("runtime", ["idl/runtime"]),
    ("processes", ["agent/node", "agent/bridge_node", "agent/examples", "sim/node", "monitor/node", "monitor/live_join",
                   "monitor/live_view", "monitor/recording/taps", "deploy/programs"]),
]
TOPS = ["agent", "sim", "monitor", "idl", "deploy"]
INCLUDE = re.compile(r'\s*#\s*include\s+"([^"]+)"')


def layer_of(rel):
    best = None
    for i, (_, paths) in enumerate(LAYERS):
        for p in paths:
            if (rel == p or rel.startswith(p + "/")) and (best is None or len(p) > best[1]):
                best = (i, len(p))
    return None if best is None else best[0]


def sources(root):
    for top in TOPS:
        for folder, _, files in os.walk(os.path.join(root, top)):
            for f in sorted(files):
                if f.endswith((".h", ".cpp")):
                    yield os.path.relpath(os.path.join(folder, f), root)


def main(root):
    headers = {}  # "swa/x/y.h" -> its file
    for rel in sources(root):
        m = re.search(r"/include/(swa/.+\.h)$", rel)
        if m:
            headers.setdefault(m.group(1), rel)
    problems = []
    for rel in sources(root):
        layer = layer_of(rel)
        if layer is None:
            problems.append(f"{rel}: in no layer (tests/layers/check_layers.py, ARCHITECTURE.md)")
            continue
        with open(os.path.join(root, rel), errors="replace") as f:
            for n, line in enumerate(f, 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                target = headers.get(m.group(1))
                if target is None:  # a header beside the file
                    beside = os.path.normpath(os.path.join(os.path.dirname(rel), m.group(1)))
                    target = beside if os.path.exists(os.path.join(root, beside)) else None
                if target is None:  # generated code, or a header outside the tree
                    continue
                to = layer_of(target)
                if to is not None and to > layer:
                    problems.append(f"{rel}:{n}: includes {m.group(1)} ({target}): {LAYERS[layer][0]} -> "
                                    f"{LAYERS[to][0]}, against the layer order")
    for p in problems:
        print(p)
    print(f"check_layers: {len(problems)} problem(s) in the include order of {root}")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
