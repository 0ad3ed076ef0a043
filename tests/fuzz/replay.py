#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""replay.py PT CORPUS [-j N] [--timeout S] [--only SUBSTRING]: runs every case of CORPUS/cases
(written by gen_corpus.py) against the pt binary PT, built with ASan+UBSan, and checks that each
one ends as its case.json expects: exit 0, or a non-zero exit whose last stderr line is one
"pt: ..." message. A signal, a sanitizer report, a hang (over --timeout seconds: 300 by default, far above any
healthy case even cold and under load, so that machine load never fails a case) or a silent
non-zero exit fails the case. Memory is bounded through ASAN_OPTIONS (ulimit -v does not work
under ASan). Prints one line per failure and the closing line "fuzz-replay: N passed, N failed";
exit status 1 if any failed.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

SANITIZER_MARKS = ("AddressSanitizer", "LeakSanitizer", "UndefinedBehaviorSanitizer",
                   "runtime error:", "ThreadSanitizer", "MemorySanitizer")
# PoCL and LLVM leak by design at exit: leaks are not what this replay is about.
ASAN_OPTIONS = ("detect_leaks=0:hard_rss_limit_mb=3072:max_allocation_size_mb=2048:"
                "allocator_may_return_null=1:abort_on_error=0:handle_abort=1:"
                "handle_segv=1:detect_stack_use_after_return=0")
UBSAN_OPTIONS = "print_stacktrace=1:halt_on_error=1"


def judge(meta, rc, err, timed_out):
    """Why the run failed its expectation; None when it passed."""
    if timed_out:
        return "hang (timed out)"
    for mark in SANITIZER_MARKS:
        if mark in err:
            line = next((l for l in err.splitlines() if mark in l), mark)
            return "sanitizer: " + line.strip()[:200]
    if rc < 0:
        return "killed by signal %d" % -rc
    lines = [l for l in err.splitlines() if l.strip()]
    if rc != 0:
        last = lines[-1] if lines else ""
        if not last.startswith("pt: ") or last.startswith("pt: warning:"):
            return "exit %d without a one-line 'pt: ...' message (stderr ends: %r)" % (rc, last[:200])
        if meta["expect"] == "ok":
            return "expected success, got exit %d: %s" % (rc, last[:200])
        if meta.get("needle") and meta["needle"] not in last:
            return "message lacks %r: %s" % (meta["needle"], last[:200])
    elif meta["expect"] == "error":
        return "expected an error, got exit 0"
    return None


def run_case(pt, repo, cache, folder, timeout):
    with open(os.path.join(folder, "case.json")) as f:
        meta = json.load(f)
    work = tempfile.mkdtemp(prefix="pt-fuzz-")
    try:
        for name in os.listdir(folder):
            if name != "case.json":
                shutil.copy(os.path.join(folder, name), work)
        # PoCL's own cache is shared too, so that a case with a cache home of its own does not
        # compile the kernels again.
        env = dict(os.environ, ASAN_OPTIONS=ASAN_OPTIONS, UBSAN_OPTIONS=UBSAN_OPTIONS,
                   XDG_CACHE_HOME=cache, PT_FUZZ_CACHE=cache,
                   POCL_CACHE_DIR=os.path.join(cache, "pocl"))
        env.pop("PT_NO_CACHE", None)
        if meta.get("setup"):
            subprocess.run(["sh", "-c", meta["setup"]], cwd=work, env=env, timeout=60,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for key, value in meta["env"].items():
            if value is None:
                env.pop(key, None)
            else:
                env[key] = value
        args = [os.fsencode(a.replace("{repo}", repo)) for a in meta["args"]]
        timed_out = False
        start = time.monotonic()
        try:
            proc = subprocess.run([pt] + args, cwd=work, env=env,
                                  timeout=meta.get("timeout") or timeout,
                                  stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.PIPE)
            rc, err = proc.returncode, proc.stderr.decode("utf-8", "replace")
        except subprocess.TimeoutExpired as e:
            timed_out, rc, err = True, -9, (e.stderr or b"").decode("utf-8", "replace")
        seconds = time.monotonic() - start
        return judge(meta, rc, err, timed_out), err, meta.get("known"), seconds
    finally:
        subprocess.run(["chmod", "-R", "u+rwx", work], stderr=subprocess.DEVNULL)
        shutil.rmtree(work, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("pt")
    parser.add_argument("corpus")
    parser.add_argument("-j", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=300)
    parser.add_argument("--only", default="")
    parser.add_argument("-v", action="store_true", help="print stderr of failing cases")
    a = parser.parse_args()
    pt = os.path.abspath(a.pt)
    repo = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    cases_dir = os.path.join(a.corpus, "cases")
    folders = [os.path.join(cases_dir, n) for n in sorted(os.listdir(cases_dir)) if a.only in n]
    # One warm-up render fills the kernel cache the cases share (and copy, to damage it).
    cache = os.path.abspath(os.path.join(a.corpus, "cache"))
    os.makedirs(cache, exist_ok=True)
    warm = tempfile.mkdtemp(prefix="pt-fuzz-warm-")
    with open(os.path.join(warm, "tri.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    # Twice: PoCL's programs are kept by PoCL (pt's entry is a marker), and the cases that damage
    # a program binary need one too (PT_CACHE_BINARIES=1).
    for binaries in ("0", "1"):
        subprocess.run([pt, "render", "tri.obj", "--width", "8", "--height", "8", "--spp", "1",
                        "--device", "cpu", "--quiet", "-o", "o.png"], cwd=warm,
                       env=dict(os.environ, ASAN_OPTIONS=ASAN_OPTIONS, XDG_CACHE_HOME=cache,
                                POCL_CACHE_DIR=os.path.join(cache, "pocl"),
                                PT_CACHE_BINARIES=binaries),
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    shutil.rmtree(warm, ignore_errors=True)
    passed = failed = 0
    durations = []
    started = time.monotonic()
    with ThreadPoolExecutor(max_workers=a.j) as pool:
        results = pool.map(lambda f: (f, run_case(pt, repo, cache, f, a.timeout)), folders)
        for folder, (problem, err, known, seconds) in results:
            durations.append((seconds, os.path.basename(folder)))
            if problem is None:
                passed += 1
                if known:
                    print("FIXED %s: passes now; remove its 'known' mark" % os.path.basename(folder))
                continue
            if known:
                print("KNOWN %s: %s (%s)" % (os.path.basename(folder), problem, known))
                continue
            failed += 1
            print("FAIL %s: %s" % (os.path.basename(folder), problem))
            if a.v:
                print("  " + "\n  ".join(err.splitlines()[-15:]))
            sys.stdout.flush()
    durations.sort(reverse=True)
    print("fuzz-replay: %d cases in %.0f s, slowest: " % (len(folders), time.monotonic() - started)
          + ", ".join("%s %.1f s" % (n, t) for t, n in durations[:4]))
    print("fuzz-replay: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
