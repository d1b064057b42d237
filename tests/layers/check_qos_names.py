#!/usr/bin/env python3
"""QoS profile names have one home (issue #47): idl/runtime/dds/profiles.xml defines the profiles and
idl/runtime/dds/include/swa/dds/qos_profiles.h names each once as a constant. Checked: the two lists are the same, and no
other C++ file under agent/, sim/, monitor/, idl/, deploy/ or tests/ writes a profile's name as a string literal.

  check_qos_names.py ROOT        exit 0: one home; 1: one line per difference or stray literal
"""
import os
import re
import sys

XML = "idl/runtime/dds/profiles.xml"
HEADER = "idl/runtime/dds/include/swa/dds/qos_profiles.h"
TOPS = ["agent", "sim", "monitor", "idl", "deploy", "tests"]


def main(root):
    with open(os.path.join(root, XML)) as f:
        in_xml = re.findall(r'profile_name="([^"]+)"', f.read())
    with open(os.path.join(root, HEADER)) as f:
        in_header = re.findall(r'constexpr const char\* k\w+ = "([^"]+)";', f.read())
    problems = []
    for name in sorted(set(in_xml) - set(in_header)):
        problems.append(f"{XML}: profile {name} has no constant in {HEADER}")
    for name in sorted(set(in_header) - set(in_xml)):
        problems.append(f"{HEADER}: {name} is no profile of {XML}")
    for name in sorted({n for n in in_header if in_header.count(n) > 1}):
        problems.append(f"{HEADER}: {name} named twice")
    literal = re.compile('"(' + "|".join(map(re.escape, in_xml)) + ')"') if in_xml else None
    for top in TOPS:
        for folder, _, files in os.walk(os.path.join(root, top)):
            for f in sorted(files):
                rel = os.path.relpath(os.path.join(folder, f), root)
                if not f.endswith((".h", ".cpp")) or rel == HEADER:
                    continue
                with open(os.path.join(root, rel), errors="replace") as src:
                    for n, line in enumerate(src, 1):
                        for m in literal.finditer(line) if literal else []:
                            problems.append(f"{rel}:{n}: the profile name \"{m.group(1)}\" written out (use "
                                            f"swa::dds::qos, {HEADER})")
    for p in problems:
        print(p)
    print(f"check_qos_names: {len(problems)} problem(s); {len(set(in_xml))} profiles in {XML}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
