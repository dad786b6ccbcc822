#!/usr/bin/env python3
"""Mutation testing: plants each bug of a hand-written list, one at
a time, in a scratch copy of the tree, rebuilds what it changed, and runs the
tests that cover the changed file. A mutant the tests catch is *killed*; one
they pass is a *survivor*, a gap in the tests (or an equivalent mutant, which
must then be explained). The score is killed / (killed + survived).

The list (tests/mutation/mutants.txt) holds blocks:
    @ FILE | TESTS | what the bug does
    - text in FILE (one or more lines), found exactly once
    + what it becomes (one or more lines)
FILE is relative to the project's root; TESTS a ctest -R regular expression; the three
fields are separated by " | " (a bar with a space on each side).
Blank lines and lines starting with # are ignored. To add a mutant, write such
a block: a realistic single bug, as a reviewer would plant it (a wrong
comparison, a lost wrap, an off-by-one, a skipped check), with a snippet that
occurs once in the file. `--check` validates the list without building.

usage: run_mutants.py [--list FILE] [--work DIR] [--only N[-M][,N...] | --sample K] [--check]
                      [--check-selection BUILD]
The baseline runs the union of the chosen mutants' tests, resolved to test names one
expression at a time (`ctest -N -R`), so no single regular expression grows with the list
(CMake's allow only 10 parenthesised groups). `--check-selection BUILD` resolves the full
run's selection in a configured build and checks it, running no test and planting nothing.
Needs a configured build of its own (made in WORK/build on the first run;
only what a mutant touches is rebuilt after that). A survivor whose
description starts with EQUIVALENT was shown to change no behaviour (its probe
is named there); it counts as a survivor in the score all the same. Exit 0
when every survivor is such a one and the score reaches --min-score; 1
otherwise, or on a broken list.
"""
import argparse
import os
import re
import resource
import shutil
import subprocess
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


class Mutant:
    def __init__(self, number, path, tests, what, before, after, line):
        self.number, self.path, self.tests, self.what = number, path, tests, what
        self.before, self.after, self.line = before, after, line


def parse(list_path):
    mutants, errors = [], []
    lines = open(list_path).read().split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.strip() or line.startswith("#"):
            i += 1
            continue
        start = i
        parts = [p.strip() for p in line[2:].split(" | ", 2)] if line.startswith("@ ") else []
        i += 1
        before, after = [], []
        while i < len(lines) and (lines[i].startswith("- ") or lines[i] == "-"):
            before.append(lines[i][2:])
            i += 1
        while i < len(lines) and (lines[i].startswith("+ ") or lines[i] == "+"):
            after.append(lines[i][2:])
            i += 1
        if len(parts) != 3 or not before or not after:
            errors.append(f"{list_path}:{start + 1}: a mutant is '@ FILE | TESTS | what', then '- before' "
                          f"lines, then '+ after' lines")
            continue
        mutants.append(Mutant(len(mutants) + 1, parts[0], parts[1], parts[2], "\n".join(before), "\n".join(after),
                              start + 1))
    return mutants, errors


def validate(mutants, root):
    errors = []
    for m in mutants:
        path = os.path.join(root, m.path)
        if not os.path.exists(path):
            errors.append(f"mutant {m.number} (line {m.line}): no file {m.path}")
            continue
        count = open(path).read().count(m.before)
        if count != 1:
            errors.append(f"mutant {m.number} (line {m.line}): '{m.before}' occurs {count} times in {m.path}")
        if m.before == m.after:
            errors.append(f"mutant {m.number} (line {m.line}): changes nothing")
        try:
            re.compile(m.tests)
        except re.error as e:
            errors.append(f"mutant {m.number} (line {m.line}): bad test expression: {e}")
    return errors


def remove_stale(src, kept):
    """Files of an earlier copy that the tree no longer has (moved or deleted) removed, so that they are not
    built or included in place of the tree's own; the links to the set-up's folders are left alone."""
    for folder, dirs, names in os.walk(src):
        dirs[:] = [d for d in dirs if not os.path.islink(os.path.join(folder, d))]
        for name in names:
            path = os.path.join(folder, name)
            if not os.path.islink(path) and os.path.relpath(path, src) not in kept:
                os.remove(path)


def scratch_copy(work):
    """The tracked files (and the working tree's changes) in WORK/src, with the
    set-up's models and Python and the team's data reachable as in the tree."""
    src = os.path.join(work, "src")
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT, capture_output=True, text=True,
                           check=True).stdout.split("\n")
    for f in files:
        if not f or not os.path.isfile(os.path.join(ROOT, f)):
            continue
        target = os.path.join(src, f)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        if not os.path.exists(target) or open(target, "rb").read() != open(os.path.join(ROOT, f), "rb").read():
            shutil.copy(os.path.join(ROOT, f), target)  # stamped now, not with the tree's time: it must rebuild
    remove_stale(src, {f for f in files if f})
    for link in (".models", ".venv", ".third_party"):
        if os.path.exists(os.path.join(ROOT, link)) and not os.path.lexists(os.path.join(src, link)):
            os.symlink(os.path.join(ROOT, link), os.path.join(src, link))
    shared = os.path.join(work, "shared")
    if not os.path.lexists(shared):
        os.symlink(os.path.abspath(os.path.join(ROOT, "..", "shared")), shared)
    return src


def build(build_dir, src, options=()):
    if not os.path.exists(os.path.join(build_dir, "build.ninja")):
        subprocess.run(["cmake", "-S", src, "-B", build_dir, "-G", "Ninja", "-DHKF_BUILD_BENCHMARKS=OFF", *options],
                       check=True, capture_output=True)
    result = subprocess.run(["cmake", "--build", build_dir, "-j", str(os.cpu_count() or 2)], capture_output=True,
                            text=True)
    return result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]


def list_tests(build_dir, expression):
    """The names of the tests that `ctest -R expression` selects (nothing is run)."""
    result = subprocess.run(["ctest", "-N", "-R", expression], cwd=build_dir, capture_output=True, text=True)
    complaint = re.findall(r"RegularExpression::compile\(\): .*", result.stdout + result.stderr)
    if result.returncode != 0 or complaint:
        raise ValueError(f"ctest cannot use the expression '{expression}': {' '.join(complaint) or result.stderr}")
    return re.findall(r"^\s*Test\s+#\d+: (\S+)$", result.stdout, re.M)


def names_expression(names):
    """One ctest -R expression, without groups, that selects exactly these tests."""
    return "|".join(f"^{re.escape(n)}$" for n in sorted(names))


def selection(build_dir, chosen):
    """The baseline's test names and expression, and the errors: an expression that ctest
    refuses or that selects no test, or a baseline expression that selects other tests."""
    names, errors = set(), []
    for expression in sorted({m.tests for m in chosen}):
        try:
            found = list_tests(build_dir, expression)
        except ValueError as e:
            errors.append(str(e))
            continue
        if not found:
            users = [str(m.number) for m in chosen if m.tests == expression]
            errors.append(f"the expression '{expression}' (mutants {', '.join(users)}) selects no test")
        names.update(found)
    baseline = names_expression(names)
    if names and not errors:
        try:
            listed = set(list_tests(build_dir, baseline))
        except ValueError as e:
            errors.append(str(e))
        else:
            if listed != names:
                errors.append(f"the baseline expression selects {len(listed)} tests, not the {len(names)} wanted")
    return sorted(names), baseline, errors


MAX_FILE_BYTES = 1 << 30  # no test writes a file near 1 GiB: a mutant that loops writing fails, not fills the disk


def limit_file_size():
    """In the tests' process (and so their children): files larger than MAX_FILE_BYTES are refused (SIGXFSZ)."""
    resource.setrlimit(resource.RLIMIT_FSIZE, (MAX_FILE_BYTES, MAX_FILE_BYTES))


def run_tests(build_dir, tests, timeout):
    result = subprocess.run(["ctest", "-R", tests, "-j", str(os.cpu_count() or 2), "--timeout", str(timeout),
                             "--stop-on-failure"], cwd=build_dir, capture_output=True, text=True,
                            preexec_fn=limit_file_size)
    ran = re.search(r"tests passed, (\d+) tests failed out of (\d+)", result.stdout)
    count = int(ran.group(2)) if ran else 0
    return result.returncode == 0, count, result.stdout


def mutant_numbers(text):
    """--only's value: numbers and ranges, comma-separated ("3,7,242-255"), as a set; a clear error otherwise."""
    wanted = set()
    for part in text.split(","):
        bounds = part.strip().split("-")
        try:
            if len(bounds) not in (1, 2):
                raise ValueError
            low, high = int(bounds[0]), int(bounds[-1])
        except ValueError:
            raise argparse.ArgumentTypeError(f"{part.strip()!r} is not a mutant number or a range N-M") from None
        if low < 1 or high < low:
            raise argparse.ArgumentTypeError(f"{part.strip()!r}: a range runs from 1 up, low to high")
        wanted.update(range(low, high + 1))
    return wanted


def arguments():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--list", default=os.path.join(ROOT, "tests", "mutation", "mutants.txt"))
    parser.add_argument("--work", default=os.path.join(ROOT, "out", "mutate"))
    parser.add_argument("--only", default=None, type=mutant_numbers,
                        help="mutant numbers, comma-separated, each a number or a range (3,7,242-255)")
    parser.add_argument("--sample", type=int, default=0, help="every K-th mutant only (a fixed sample)")
    parser.add_argument("--check", action="store_true", help="validate the list, build and run nothing")
    parser.add_argument("--check-selection", metavar="BUILD",
                        help="resolve the full run's tests in this configured build and check them; run nothing")
    parser.add_argument("--libhkf-only", action="store_true",
                        help="only libhkf's mutants, in a build of libhkf and its tests alone (-DHKF_BUILD_TOOLS=OFF): "
                             "the quick sample in ./run test")
    parser.add_argument("--min-score", type=float, default=1.0, help="exit 0 at this score or above")
    parser.add_argument("--timeout", type=int, default=300, help="seconds per test")
    return parser.parse_args()


def check_selection(build_dir, mutants):
    """--check-selection: the full run's tests resolved in a configured build; the exit status."""
    names, _, errors = selection(os.path.abspath(build_dir), mutants)
    if errors:
        print("\n".join(f"run_mutants: {e}" for e in errors), file=sys.stderr)
        return 1
    print(f"run_mutants: the full run's baseline selects {len(names)} tests for "
          f"{len({m.tests for m in mutants})} expressions: {' '.join(names)}")
    return 0


LIBHKF_TESTS = r"^hkf\.libhkf\."


def chosen_mutants(mutants, args):
    """The mutants to run. --libhkf-only: libhkf's alone, each judged by libhkf's own tests (a library that
    cockpit controllers link alone must catch its own bugs): one whose tests are the programs' (a table of
    models' column that only hkf-filter reads) runs against every libhkf test instead."""
    chosen = mutants
    if args.libhkf_only:
        chosen = [m for m in mutants if m.path.startswith("libhkf/")]
        for m in chosen:
            if not m.tests.startswith(LIBHKF_TESTS):
                m.tests = LIBHKF_TESTS
    if args.only:
        return [m for m in chosen if m.number in args.only]
    return chosen[::args.sample] if args.sample else chosen


def green_baseline(args, chosen):
    """The scratch copy built and the chosen mutants' tests passing on it: (src, build dir, cmake options), or
    None (said)."""
    work = os.path.abspath(args.work)
    src = scratch_copy(work)
    build_dir = os.path.join(work, "build-libhkf" if args.libhkf_only else "build")
    options = ["-DHKF_BUILD_TOOLS=OFF"] if args.libhkf_only else []
    ok, log = build(build_dir, src, options)
    if not ok:
        print(log, file=sys.stderr)
        print("run_mutants: the unmutated tree does not build", file=sys.stderr)
        return None
    names, baseline, errors = selection(build_dir, chosen)
    if errors:
        print("\n".join(f"run_mutants: {e}" for e in errors), file=sys.stderr)
        return None
    ok, count, log = run_tests(build_dir, baseline, args.timeout)
    if not ok or count == 0:
        print(log[-3000:], file=sys.stderr)
        print("run_mutants: the tests fail (or none match) on the unmutated tree", file=sys.stderr)
        return None
    print(f"run_mutants: baseline green ({count} tests); {len(chosen)} mutants to run", flush=True)
    return src, build_dir, options


def run_mutant(m, src, build_dir, options, timeout):
    """One mutant planted, built and its tests run, the file restored: ("killed" | "survived" | "stillborn", what)."""
    path = os.path.join(src, m.path)
    original = open(path).read()
    try:
        with open(path, "w") as f:
            f.write(original.replace(m.before, m.after, 1))
        ok, log = build(build_dir, src, options)
        if not ok:
            return "stillborn", "does not build (fix the list)"
        passed, count, log = run_tests(build_dir, m.tests, timeout)
        if passed:
            return "survived", f"SURVIVED {count} tests"
        failed = re.findall(r"\d+ - (\S+) \(", log)
        return "killed", f"killed by {', '.join(failed[:3]) or 'the tests'}"
    finally:
        with open(path, "w") as f:
            f.write(original)


def report(chosen, killed, survivors, stillborn, wall, min_score):
    """The score and the survivors; the exit status."""
    scored = killed + len(survivors)
    score = killed / scored if scored else 0.0
    unexplained = [m for m in survivors if not m.what.startswith("EQUIVALENT")]
    print(f"run_mutants: {killed} of {scored} mutants killed: score {100 * score:.1f} %"
          + (f"; {len(stillborn)} did not build" if stillborn else "")
          + f"; wall time {wall / 60:.1f} min ({len(chosen)} mutants, {os.cpu_count()} cores)")
    for m in survivors:
        print(f"  survivor [{m.number}] {m.path} (line {m.line} of the list): {m.what}")
    if survivors:
        print(f"run_mutants: {len(survivors) - len(unexplained)} survivors marked EQUIVALENT (each with its probe), "
              f"{len(unexplained)} unexplained")
    return 0 if score >= min_score and not unexplained and not stillborn else 1


def main():
    args = arguments()
    mutants, errors = parse(args.list)
    errors += validate(mutants, ROOT)
    if errors:
        print("\n".join(errors), file=sys.stderr)
        return 1
    print(f"run_mutants: {len(mutants)} mutants in {os.path.relpath(args.list, ROOT)}, all valid", flush=True)
    if args.check:
        return 0
    if args.check_selection:
        return check_selection(args.check_selection, mutants)
    run_started = time.time()
    chosen = chosen_mutants(mutants, args)
    prepared = green_baseline(args, chosen)
    if prepared is None:
        return 1
    src, build_dir, options = prepared
    outcome = {"killed": [], "survived": [], "stillborn": []}
    started = time.time()
    for m in chosen:
        kind, verdict = run_mutant(m, src, build_dir, options, args.timeout)
        outcome[kind].append(m)
        print(f"[{m.number:3d}] {m.path}: {m.what}: {verdict} ({time.time() - started:.0f} s)", flush=True)
    status = report(chosen, len(outcome["killed"]), outcome["survived"], outcome["stillborn"],
                    time.time() - run_started, args.min_score)
    build(build_dir, src, options)  # leave the scratch build unmutated
    return status


if __name__ == "__main__":
    sys.exit(main())
