#!/usr/bin/env python3
"""Runs one case of the bad-input corpus (tests/data/bad/cases.yaml) through the program.

Asserts what every case promises:
  - the exit code is the expected one (2 bad input, 1 runtime failure), and not a signal;
  - each expected text is in stderr (the culprit: file, key, value), and stderr is not empty;
  - no hang: the program ends within the case's time limit (it is killed and the case fails if not);
  - no partial output: the output folder does not exist afterwards, or, when it held files before
    the run, holds exactly those files with the same bytes; no staging folder is left anywhere in
    the case's scratch folder.
Cases that need a mount (read-only, full) end with exit code 77 (ctest: skipped) and say why when
the mount cannot be made.

Usage: run_bad_case.py EXE CORPUS_DIR SCRATCH_DIR CASE_NAME
"""
import os
import shutil
import signal
import subprocess
import sys
import time

import yaml

SKIP = 77


def fail(case, why, result=None):
    print("FAIL %s: %s" % (case["name"], why))
    if result is not None:
        print("exit code: %s\n--- stdout ---\n%s\n--- stderr ---\n%s" % result)
    sys.exit(1)


def snapshot(folder):
    """{relative path: bytes} of every file below `folder` (None when it does not exist)."""
    if not os.path.isdir(folder):
        return None
    files = {}
    for root, _, names in os.walk(folder):
        for n in names:
            p = os.path.join(root, n)
            with open(p, "rb") as f:
                files[os.path.relpath(p, folder)] = f.read()
    return files


def mount_tmpfs(where, options):
    os.makedirs(where, exist_ok=True)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", where], capture_output=True, text=True)
    return r.returncode == 0, r.stderr.strip()


class Setup:
    """Prepares the scratch folder for a case's `setup` kind; returns the substitutions."""

    def __init__(self, exe, corpus, scratch, case):
        self.exe, self.corpus, self.scratch, self.case = exe, corpus, scratch, case
        self.mounts = []
        self.subs = {"data": corpus, "out": os.path.join(scratch, "out"), "scratch": scratch}

    def run(self):
        kind = self.case.get("setup", "none")
        getattr(self, "setup_" + kind.replace("-", "_"))()
        return self.subs

    def setup_none(self):
        pass

    def copy_as(self, source, relative):
        target = os.path.join(self.scratch, relative)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(self.corpus, source), target)
        return target

    def setup_non_ascii_path(self):
        self.subs["input"] = self.copy_as(self.case["input"], "données-été/Brüst ñ 乳房.nii.gz")
        self.subs["out"] = os.path.join(self.scratch, "sortie-ü")

    def setup_long_path(self):
        # 40 nested folders of 120 characters: 4,800 characters, over PATH_MAX (4,096).
        parts = ["d%02d_" % i + "x" * 116 for i in range(40)]
        self.subs["input"] = os.path.join(self.scratch, *parts, "labels.nii.gz")

    def setup_directory_input(self):
        self.subs["input"] = os.path.join(self.scratch, "folder.nii.gz")
        os.makedirs(self.subs["input"])

    def setup_phantom(self):
        p = os.path.join(self.scratch, "phantom.nii.gz")
        subprocess.run([self.exe, "phantom", "--out", p], check=True, capture_output=True, timeout=120)
        self.subs["input"] = p

    def setup_existing_output(self):
        out = self.subs["out"]
        os.makedirs(out)
        for name, text in (("mesh.vtu", "previous mesh\n"), ("report.json", "{\"previous\": true}\n")):
            with open(os.path.join(out, name), "w") as f:
                f.write(text)
        if self.case.get("phantom"):
            self.setup_phantom()

    def setup_read_only_mount(self):
        self.output_on_tmpfs("ro", "ro,size=1m", "a read-only tmpfs")

    def setup_full_disk(self):
        self.output_on_tmpfs("full", "size=%s" % self.case.get("tmpfs_size", "16k"), "a small tmpfs to fill")

    def output_on_tmpfs(self, folder, options, what):
        """Puts the output folder on a tmpfs mounted with `options`; skips the case without one."""
        where = os.path.join(self.scratch, folder)
        ok, err = mount_tmpfs(where, options)
        if not ok:
            print("SKIP: cannot mount %s (%s)" % (what, err))
            sys.exit(SKIP)
        self.mounts.append(where)
        self.subs["out"] = os.path.join(where, "out")

    def cleanup(self):
        for m in self.mounts:
            subprocess.run(["umount", m], capture_output=True)


def run_case(exe, corpus, scratch, case):
    setup = Setup(exe, corpus, scratch, case)
    try:
        subs = setup.run()
        args = [a.format(**subs) for a in case["args"]]
        out = subs["out"]
        before = snapshot(out)
        env = dict(os.environ)
        env.update({k: str(v) for k, v in case.get("env", {}).items()})
        limit = float(case.get("timeout", 60))
        start = time.monotonic()
        proc = subprocess.Popen([exe] + args, cwd=scratch, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, errors="replace")
        first_line = ""
        if "signal_after" in case:
            # Counted from the run's first progress line, printed after main() has installed the
            # signal handlers: a delay counted from the start raced a slow start (sanitizers, load).
            first_line = proc.stdout.readline()
            time.sleep(float(case["signal_after"]))
            if proc.poll() is None:
                proc.send_signal(getattr(signal, case.get("signal", "SIGINT")))
        try:
            stdout, stderr = proc.communicate(timeout=max(0.0, limit - (time.monotonic() - start)))
            stdout = first_line + stdout
        except subprocess.TimeoutExpired:
            proc.kill()
            stdout, stderr = proc.communicate()
            fail(case, "no result within %.0f s (hang)" % limit, (None, stdout, stderr))
        elapsed = time.monotonic() - start
        result = (proc.returncode, stdout, stderr)
        if proc.returncode < 0:
            fail(case, "ended by signal %d (crash)" % -proc.returncode, result)
        if proc.returncode != case["exit"]:
            fail(case, "exit code %d, expected %d" % (proc.returncode, case["exit"]), result)
        if not stderr.strip():
            fail(case, "nothing on stderr", result)
        for text in case["message"]:
            text = text.format(**subs)
            if text not in stderr:
                fail(case, "'%s' not in the message" % text, result)
        after = snapshot(out)
        if before is None and after is not None:
            fail(case, "output folder %s left behind: %s" % (out, sorted(after)), result)
        if before is not None and after != before:
            fail(case, "existing output in %s changed: %s -> %s" % (out, sorted(before), sorted(after or {})), result)
        for root, dirs, _ in os.walk(scratch):
            for d in dirs:
                if d.startswith(".tissuemesh-staging"):
                    fail(case, "staging folder left behind: %s" % os.path.join(root, d), result)
        print("ok %s: exit %d in %.2f s: %s" % (case["name"], proc.returncode, elapsed, stderr.strip().splitlines()[-1][:300]))
    finally:
        setup.cleanup()


def main():
    exe, corpus, scratch, name = sys.argv[1:5]
    with open(os.path.join(corpus, "cases.yaml"), encoding="utf-8") as f:
        cases = {c["name"]: c for c in yaml.safe_load(f)}
    if name not in cases:
        print("no case named %s" % name)
        return 1
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    run_case(os.path.abspath(exe), os.path.abspath(corpus), os.path.abspath(scratch), cases[name])
    return 0


if __name__ == "__main__":
    sys.exit(main())
