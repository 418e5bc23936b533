#!/usr/bin/env python3
"""Checks that the project's docs cover every configuration key and every command.

Keys: the program prints the effective config of each shipped config (`tissuemesh mesh ...
--print-config`: every section with its defaults filled in); every key path in it must appear in
docs/configuration.md as `a.b.c` in backticks. List items are written `list[].key`, maps keyed by
a tissue name `map.<tissue>.key`. Conversely, every key path the configuration reference
documents must be one the program knows: the first segment must be a section it prints.
Commands: every subcommand `tissuemesh --help` lists must have a heading in docs/commands.md and
a row in the README's commands table.

Usage: check_config_docs.py TISSUEMESH REPO_ROOT
"""
import glob
import os
import re
import subprocess
import sys

import yaml

EXE, ROOT = sys.argv[1], os.path.abspath(sys.argv[2])
TISSUE_MAPS = {"materials", "direct.cell_size_per_tissue_mm", "tetgen.max_volume_mm3"}


def key_paths(node, prefix, out):
    if isinstance(node, dict):
        if not node and prefix:
            out.add(prefix)
        for k, v in node.items():
            seg = "<tissue>" if prefix in TISSUE_MAPS else str(k)
            key_paths(v, f"{prefix}.{seg}" if prefix else seg, out)
    elif isinstance(node, list) and node and all(isinstance(i, dict) for i in node):
        for item in node:
            key_paths(item, prefix + "[]", out)
    else:
        out.add(prefix)


def main():
    configs = sorted(glob.glob(os.path.join(ROOT, "configs", "*.yaml")) +
                     glob.glob(os.path.join(ROOT, "bench", "configs", "*.yaml")))
    keys, sections = set(), set()
    for cfg in configs:
        text = subprocess.run([EXE, "mesh", "labels.nii.gz", "-c", cfg, "-o", "unused", "--print-config"],
                              check=True, capture_output=True, text=True).stdout
        doc = yaml.safe_load(text)
        sections.update(doc.keys())
        key_paths(doc, "", keys)
    reference = open(os.path.join(ROOT, "docs/configuration.md"), encoding="utf-8").read()
    documented = set(re.findall(r"^\|\s*`([^`]+)`", reference, re.M))
    findings = [f"docs/configuration.md: key `{k}` is not documented" for k in sorted(keys)
                if k not in documented and f"`{k}`" not in reference]
    for k in sorted(documented):
        first = re.split(r"[.\[]", k)[0]
        if first not in sections:
            findings.append(f"docs/configuration.md: `{k}` is not a key of any section the program knows")

    help_text = subprocess.run([EXE, "--help"], check=True, capture_output=True, text=True).stdout
    commands = re.findall(r"^  (\w+)\s{2,}", help_text.split("Subcommands:")[1], re.M)
    commands_doc = open(os.path.join(ROOT, "docs/commands.md"), encoding="utf-8").read()
    readme = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
    for c in commands:
        if not re.search(rf"^#+ .*`?tissuemesh {c}\b", commands_doc, re.M) and \
           not re.search(rf"^#+ .*\b{c}\b", commands_doc, re.M):
            findings.append(f"docs/commands.md: no section for the command '{c}'")
        if not re.search(rf"^\|.*\b{c}\b", readme, re.M):
            findings.append(f"README.md: the commands table has no row for '{c}'")
    readme_lines = readme.count("\n")
    if readme_lines > 300:
        findings.append(f"README.md: {readme_lines} lines (at most 300: method and reference go to docs/)")
    for f in findings:
        print(f)
    print(f"check_config_docs: {len(keys)} keys from {len(configs)} configs, {len(commands)} commands, "
          f"{len(findings)} finding(s)")
    return 1 if findings or not keys or not commands else 0


if __name__ == "__main__":
    sys.exit(main())
