#!/usr/bin/env python3
"""Checks that the repository's text points only at things a user can open.

Every tracked text file (sources, scripts, configs, docs, the README) is scanned for
  - issue numbers ("issue #5", "issues 5 and 6", a bare "#6"): history belongs in git log;
  - references to files the repository does not contain: a path that starts with one of the
    project's folders (core/..., docs/..., the retired mesher/...) or any *.md / *.txt name must
    exist, relative to the repository root or to the file that mentions it;
  - notes that live outside the repository (a shared/ or reference/ folder).
Program output is covered because the strings a program prints are in its sources.

Usage: check_references.py REPO_ROOT   (exit 0 when clean; otherwise every finding, then exit 1)
"""
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
FOLDERS = ("core", "image", "surface", "quality", "volume", "pipeline", "materials", "fe_export",
           "solver_check", "app", "configs", "docs", "examples", "tests", "bench", "scripts", "cmake",
           "mesher")
TEXT_EXT = (".h", ".cpp", ".hpp", ".c", ".py", ".sh", ".cmake", ".txt", ".md", ".yaml", ".yml",
            ".in", ".js", ".html", ".csv", ".json")

ISSUE = re.compile(r"(?i)\bissues?\s*#?\s*\d+|(?<![\w&])#\d+\b")
OUTSIDE = re.compile(r"(?<![\w.])(?:\.\./)*(?:shared|reference)/[\w./-]+")
PATH = re.compile(r"(?<![\w./<-])((?:\.\./|\./)?(?:%s)/[\w./-]*[\w-])" % "|".join(FOLDERS))
DOC = re.compile(r"(?<![\w/.-])([\w-]+(?:/[\w.-]+)*\.md)\b")
OUTSIDE_NAMES = re.compile(r"seed-paper\.txt|biomech\.md|peers\.md|DESIGN\.md")
# Paths a test creates in its scratch folder (they name no file of the repository).
SCRATCH = {"materials/ucl.yaml"}


def tracked_files():
    out = subprocess.check_output(["git", "-C", ROOT, "ls-files", "-z"]).decode()
    return [p for p in out.split("\0") if p]


def exists(ref, where):
    ref = ref.rstrip(".")
    # relative to the root, to the mentioning file, or to configs/ (config files name presets so)
    for base in (ROOT, os.path.join(ROOT, os.path.dirname(where)), os.path.join(ROOT, "configs")):
        if os.path.exists(os.path.normpath(os.path.join(base, ref))):
            return True
    return False


def main():
    findings = []
    for rel in tracked_files():
        if not rel.endswith(TEXT_EXT) and os.path.basename(rel) not in ("run",):
            continue
        if rel.startswith("tests/data/"):
            continue  # inputs of tests (bad files) may hold anything
        path = os.path.join(ROOT, rel)
        if not os.path.isfile(path):
            continue
        try:
            lines = open(path, encoding="utf-8").read().splitlines()
        except UnicodeDecodeError:
            continue
        for n, line in enumerate(lines, 1):
            if rel == "tests/repo/check_references.py":
                break  # this file names the patterns it looks for
            for m in ISSUE.finditer(line):
                findings.append(f"{rel}:{n}: issue number '{m.group(0)}'")
            for m in OUTSIDE_NAMES.finditer(line):
                findings.append(f"{rel}:{n}: note outside the repository '{m.group(0)}'")
            for m in OUTSIDE.finditer(line):
                findings.append(f"{rel}:{n}: file outside the repository '{m.group(0)}'")
            for m in PATH.finditer(line):
                ref = m.group(1)
                after = line[m.end():m.end() + 1]
                if after in ("*", "<") or ref in SCRATCH:
                    continue
                if "." not in ref.split("/")[-1] and not ref.endswith("/"):
                    continue  # "quality/conformity" in prose; only file names are checked

                if not exists(ref, rel):
                    findings.append(f"{rel}:{n}: no such file or folder '{ref}'")
            for m in DOC.finditer(line):
                ref = m.group(1)
                if ref.startswith(tuple(f + "/" for f in FOLDERS)) or OUTSIDE_NAMES.search(ref):
                    continue  # checked above
                if not exists(ref, rel):
                    findings.append(f"{rel}:{n}: no such document '{ref}'")
    for f in findings:
        print(f)
    print(f"check_references: {len(findings)} finding(s)")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
