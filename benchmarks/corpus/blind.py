"""The blind protocol of issue 29: lint the tuning, the blind or the validation part of the
corpus, count the default findings per rule, and draw a seeded judging sheet (docs/precision.md).

The split is benchmarks/corpus/split.toml (by repository, with its seed). Lint results are
cached per case in CORPUS/_precision/LABEL/CASE.json (the `lint --format json` document and the
exit code), so a sheet or a count never lints again; `--fresh` lints again.

Usage:
    python benchmarks/corpus/blind.py draw-split
    python benchmarks/corpus/blind.py lint --part blind --label after [--src DIR] [--fresh]
    python benchmarks/corpus/blind.py count --part blind --label after [--label before ...]
        [--per-location]
    python benchmarks/corpus/blind.py sheet --part blind --label after --seed 2929 --per-rule 5
    python benchmarks/corpus/blind.py lint --part validation --label validation

The parts: `tuning`, `blind` (drawn with the seed, plus `added`) and `validation` (the
repositories of issue 29's own held-out corpus; neither drawn nor tuned on).

`--src DIR` runs another robotdesc source tree (PYTHONPATH=DIR), e.g. the code before a change
extracted with `git archive`, to measure "before" and "after" on the same corpus.
Each case is linted with `--jobs 1` in a process of its own (the machine may be shared).
"""

from __future__ import annotations

import argparse
import json
import os
import random
import re
import subprocess
import sys
import tomllib
from collections import Counter
from pathlib import Path

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.linting.merge import message_key

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import run_corpus  # noqa: E402  (a script beside this one, not a package)

SPLIT = HERE / "split.toml"
LINT_TIMEOUT_S = 900.0


def load_split(path: Path = SPLIT) -> dict:
    return tomllib.loads(path.read_text())


def blind_repositories(split: dict) -> set[str]:
    return set(split["blind"]) | set(split.get("added", []))


def validation_repositories(split: dict) -> set[str]:
    return set(split.get("validation", []))


PARTS = ("tuning", "blind", "validation")


def part_of(repository: str, split: dict) -> str:
    """The part a case's repository belongs to: validation (issue 29's own held-out
    repositories), blind (drawn or added), else tuning."""
    if repository in validation_repositories(split):
        return "validation"
    return "blind" if repository in blind_repositories(split) else "tuning"


def part_cases(manifest: run_corpus.Manifest, split: dict, part: str) -> list[run_corpus.Case]:
    return [c for c in manifest.cases if part_of(c.repository, split) == part]


def draw_split(manifest: run_corpus.Manifest, split: dict) -> list[str]:
    """The seeded draw of split.toml, again: the repositories of the cases, the ones added for
    issue 29 and the validation part left out, sorted, then
    `random.Random(seed).sample(..., drawn)`."""
    outside = set(split.get("added", [])) | validation_repositories(split)
    repositories = sorted({c.repository for c in manifest.cases} - outside)
    return sorted(random.Random(split["seed"]).sample(repositories, split["drawn"]))


def needed_folders(cases: list[run_corpus.Case]) -> set[str]:
    folders = set()
    for case in cases:
        folders.add(run_corpus.repo_folder(case.repository))
        folders.update(path.split("/")[0] for path in case.packages)
    return folders


def cache_file(corpus: Path, label: str, case: run_corpus.Case) -> Path:
    return corpus / "_precision" / label / f"{case.name}.json"


def lint_case(case: run_corpus.Case, corpus: Path, src: Path | None) -> dict:
    command = run_corpus.robotdesc_command("lint", case, corpus)
    command += ["--format", "json", "--jobs", "1", "-q"]
    env = dict(os.environ)
    if src is not None:
        env["PYTHONPATH"] = str(src)
    try:
        done = subprocess.run(command, capture_output=True, env=env, cwd=corpus,
                              timeout=LINT_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return {"case": case.name, "exit": None, "report": None, "stderr": "timed out"}
    try:
        report = json.loads(done.stdout)
    except json.JSONDecodeError:
        report = None
    return {"case": case.name, "exit": done.returncode, "report": report,
            "stderr": done.stderr.decode(errors="replace")[-2000:]}


def lint_part(options: argparse.Namespace) -> None:
    manifest = run_corpus.load_manifest(run_corpus.DEFAULT_MANIFEST)
    split = load_split()
    cases = run_corpus.select(part_cases(manifest, split, options.part), options.only)
    corpus = options.corpus.resolve()
    for folder in sorted(needed_folders(cases)):
        run_corpus.extract(folder, manifest.commits[folder], options.fetch_root, corpus)
    for case in cases:
        target = cache_file(corpus, options.label, case)
        if target.is_file() and not options.fresh:
            continue
        result = lint_case(case, corpus, options.src)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(json.dumps(result, indent=1))
        found = len(result["report"]["diagnostics"]) if result["report"] else "-"
        print(f"{case.name}: exit {result['exit']}, {found} findings", file=sys.stderr)


def load_results(corpus: Path, label: str, cases: list[run_corpus.Case]) -> list[dict]:
    results = []
    for case in cases:
        path = cache_file(corpus, label, case)
        if path.is_file():
            results.append(json.loads(path.read_text()))
    return results


def findings(results: list[dict]) -> list[dict]:
    """Every diagnostic of the cached results, each with its case's name."""
    return [dict(d, case=r["case"]) for r in results if r["report"]
            for d in r["report"]["diagnostics"]]


def absent_files(corpus: Path, fetch_root: Path, folder: str, commit: str) -> set[str]:
    """Absolute paths of the files of `folder` at `commit` whose blobs the fetch snapshot
    lacks (its largest files, usually meshes): an M101 on one of them is the environment,
    not the description. Cached in CORPUS/_precision/absent/FOLDER.json."""
    cached = corpus / "_precision" / "absent" / f"{folder}.json"
    if cached.is_file():
        return set(json.loads(cached.read_text()))
    mirror = run_corpus.mirror_dir(fetch_root, folder)
    entries = run_corpus.tree_entries(mirror, commit)
    check = subprocess.run(["git", f"--git-dir={mirror}", "cat-file", "--batch-check"],
                           input="".join(blob + "\n" for _m, blob, _p in entries).encode(),
                           capture_output=True, check=True).stdout.decode().splitlines()
    absent = sorted(str(corpus / folder / path) for (_m, _b, path), line in zip(entries, check)
                    if line.endswith("missing"))
    cached.parent.mkdir(parents=True, exist_ok=True)
    cached.write_text(json.dumps(absent))
    return set(absent)


FILE_MISSING_RE = re.compile(r"^mesh file '([^']*)' \(")
MISSING_RE = re.compile(r"^'package://[^']*' not found \((/[^)]*)\)")


def environment_finding(finding: dict, absent: set[str], corpus: Path) -> bool:
    """An M101 on a `package://` mesh the corpus cannot have: its blob is absent from the
    fetch snapshot, or the repository does not hold it at all (Stretch's meshes are copied in
    from another repository when the package is built). `file://` and absolute references
    are judged: where they point is what the description says."""
    if finding["code"] != "M101":
        return False
    written = FILE_MISSING_RE.match(finding["message"])
    if written is not None:  # file://$(find pkg)/...: only a blob the snapshot lacks
        return written.group(1) in absent
    match = MISSING_RE.match(finding["message"])
    if match is None:
        return False
    path = match.group(1)
    return path in absent or (path.startswith(str(corpus) + "/") and not Path(path).exists())


def per_location(every: list[dict]) -> list[dict]:
    """The findings of each case that agree in code, severity, file, line, column and message
    (the element's name aside) once, as every report counts them since they merge one problem
    per source location (robotdesc.linting.merge): for runs cached before that (`before`,
    `release`), which listed each element's finding."""
    seen: dict[tuple[object, ...], dict] = {}
    for finding in every:
        diagnostic = Diagnostic(finding["code"], finding["name"],
                                Severity.parse(finding["severity"]), finding["message"], None,
                                finding["element"])
        key = (finding["case"], finding["target"], finding["code"], finding["severity"],
               finding["file"], finding["line"], finding["column"], message_key(diagnostic))
        seen.setdefault(key, finding)
    return list(seen.values())


def count(options: argparse.Namespace) -> None:
    manifest = run_corpus.load_manifest(run_corpus.DEFAULT_MANIFEST)
    cases = part_cases(manifest, load_split(), options.part)
    corpus = options.corpus.resolve()
    manifest_commits = manifest.commits
    absent: set[str] = set()
    for folder in sorted(needed_folders(cases)):
        absent |= absent_files(corpus, options.fetch_root, folder, manifest_commits[folder])
    tables = {}
    for label in options.label:
        results = load_results(corpus, label, cases)
        every = findings(results)
        if options.per_location:
            every = per_location(every)
        tables[label] = Counter(d["code"] for d in every)
        environment = sum(1 for d in every if environment_finding(d, absent, corpus))
        tables[label]["M101 (not in corpus)"] = environment
        tables[label]["M101"] -= environment
        exits = Counter(r["exit"] for r in results)
        print(f"{label}: {len(results)} of {len(cases)} cases linted, {len(every)} findings "
              f"({len(every) - environment} without the {environment} M101 on meshes the "
              f"corpus cannot hold), exit codes {dict(exits)}")
    codes = sorted(set().union(*tables.values()))
    print("| rule | " + " | ".join(options.label) + " |")
    print("|---|" + "---|" * len(options.label))
    for code in codes:
        print(f"| {code} | " + " | ".join(str(tables[lb][code]) for lb in options.label) + " |")
    print("| total | " + " | ".join(str(sum(t.values())) for t in tables.values()) + " |")
    print("| total without M101 (not in corpus) | " + " | ".join(
        str(sum(t.values()) - t["M101 (not in corpus)"]) for t in tables.values()) + " |")


def source_line(path: str | None, line: int | None) -> str:
    if not path or not line:
        return ""
    try:
        lines = Path(path).read_text(errors="replace").splitlines()
    except OSError:
        return "(file not readable)"
    return lines[line - 1].strip()[:200] if 0 < line <= len(lines) else "(no such line)"


def sheet(options: argparse.Namespace) -> None:
    """Per rule, up to --per-rule findings drawn with the seed (all listed in a stable order
    first, then `random.Random(f"{seed}:{code}").sample`), each with its file:line and the line's text,
    and a blank verdict to fill in: true / noise / false / wrong location. M101 findings on
    meshes the corpus cannot hold (`environment_finding`) are not drawn."""
    manifest = run_corpus.load_manifest(run_corpus.DEFAULT_MANIFEST)
    cases = part_cases(manifest, load_split(), options.part)
    corpus = options.corpus.resolve()
    absent: set[str] = set()
    for folder in sorted(needed_folders(cases)):
        absent |= absent_files(corpus, options.fetch_root, folder, manifest.commits[folder])
    every = [d for d in findings(load_results(corpus, options.label, cases))
             if not environment_finding(d, absent, corpus)]
    by_code: dict[str, list[dict]] = {}
    for finding in sorted(every, key=lambda d: (d["case"], d["file"] or "", d["line"] or 0,
                                                 d["message"])):
        by_code.setdefault(finding["code"], []).append(finding)
    print(f"# judging sheet: part {options.part}, label {options.label}, seed {options.seed}, "
          f"up to {options.per_rule} per rule; verdict: true / noise / false / wrong-location")
    for code in sorted(by_code):
        pool = by_code[code]
        rng = random.Random(f"{options.seed}:{code}")  # per rule: draws do not shift
        drawn = pool if len(pool) <= options.per_rule else rng.sample(pool, options.per_rule)
        print(f"\n## {code} ({pool[0]['severity']}): {len(drawn)} of {len(pool)}")
        for d in drawn:
            where = f"{d['file']}:{d['line']}"
            if d["file"] and d["file"].startswith(str(corpus)):
                where = where[len(str(corpus)) + 1:]
            print(f"- [{d['case']}] {where}\n    {d['message']}\n"
                  f"    > {source_line(d['file'], d['line'])}\n    verdict: ")


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--corpus", type=Path, default=Path("/work/corpus"))
    parser.add_argument("--fetch-root", type=Path, default=Path("/work/.mirror"))
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("draw-split", help="print the seeded draw of split.toml again")
    lint = sub.add_parser("lint", help="lint a part's cases, cached per case")
    lint.add_argument("--part", choices=PARTS, required=True)
    lint.add_argument("--label", required=True, help="name of the cached run (e.g. before)")
    lint.add_argument("--src", type=Path, help="robotdesc source tree to run (PYTHONPATH)")
    lint.add_argument("--only", action="append", default=[], help="cases containing this")
    lint.add_argument("--fresh", action="store_true", help="lint again, ignoring the cache")
    counts = sub.add_parser("count", help="findings per rule of cached runs")
    counts.add_argument("--part", choices=PARTS, required=True)
    counts.add_argument("--label", action="append", required=True)
    counts.add_argument("--per-location", action="store_true",
                        help="count one finding per problem and source location, as reports "
                             "do now, in runs cached before reports merged them")
    judge = sub.add_parser("sheet", help="print a seeded judging sheet")
    judge.add_argument("--part", choices=PARTS, required=True)
    judge.add_argument("--label", required=True)
    judge.add_argument("--seed", type=int, default=2929)
    judge.add_argument("--per-rule", type=int, default=5)
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> None:
    options = parse_args(argv)
    if options.command == "draw-split":
        manifest = run_corpus.load_manifest(run_corpus.DEFAULT_MANIFEST)
        split = load_split()
        drawn = draw_split(manifest, split)
        print("\n".join(drawn))
        if drawn != sorted(split["blind"]):
            raise SystemExit("the draw differs from split.toml's blind list")
        return
    {"lint": lint_part, "count": count, "sheet": sheet}[options.command](options)


if __name__ == "__main__":
    main()
