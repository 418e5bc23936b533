#!/usr/bin/env python3
"""Checks that every module includes only what the module table (docs/architecture.md) allows.

Data flows one way: core <- image <- surface <- volume -> quality -> core, the pipeline runs them,
materials / fe_export / solver_check / workflows never see a mesher, and only the program (app/) sees
everything. A project header is included as "<folder>/<file>.h"; a third-party library by its own
header names (CGAL/..., tetgen.h, vtk*.h, gmsh.h).

Usage: check_module_deps.py REPO_ROOT   (exit 0 when clean; otherwise every finding, then exit 1)
"""
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")

# folder -> the project folders it may include (besides itself)
ALLOWED = {
    "core": set(),
    "image": {"core"},
    "surface": {"core", "image"},
    "quality": {"core"},
    "volume": {"core", "image", "surface", "quality"},
    "pipeline": {"core", "image", "surface", "quality", "volume"},
    "materials": {"core"},
    "fe_export": {"core", "materials"},
    "solver_check": {"core", "materials"},
    "workflows": {"core", "materials", "fe_export", "solver_check"},
    "report": {"core", "quality"},
}
# third-party headers -> the folders that may include them
THIRD_PARTY = {
    re.compile(r"^CGAL/"): {"surface", "volume"},
    re.compile(r"^tetgen\.h$"): {"volume"},
    re.compile(r"^gmsh\.h$"): {"fe_export"},
    re.compile(r"^vtk\w*\.h$"): {"core", "image", "fe_export", "report"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def main():
    findings = []
    for folder, allowed in ALLOWED.items():
        for dirpath, _, names in os.walk(os.path.join(ROOT, folder)):
            for name in sorted(names):
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, ROOT)
                for n, line in enumerate(open(path, encoding="utf-8"), 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    header = m.group(2)
                    first = header.split("/")[0]
                    if m.group(1) == '"' and first in ALLOWED and first != folder and first not in allowed:
                        findings.append(f"{rel}:{n}: {folder}/ may not include {header}")
                    for pattern, users in THIRD_PARTY.items():
                        if pattern.search(header) and folder not in users:
                            findings.append(f"{rel}:{n}: {folder}/ may not include <{header}>")
    for f in findings:
        print(f)
    print(f"check_module_deps: {len(findings)} finding(s)")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
