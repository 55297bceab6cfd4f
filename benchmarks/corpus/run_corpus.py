"""Measure robotdesc against a corpus of real ROS description packages (issue 13, items 2 and 9).

For every case in manifest.toml (a top-level xacro or URDF in a public repository, at a recorded
commit, with its xacro arguments and the package folders it needs) this script

1. extracts the repositories at the recorded commits from the `fetch` mirrors
   (`--fetch-root`, default /work/.mirror; `OWNER+NAME/repo` bare git dirs) into `--corpus`
   (default /work/corpus); nothing is downloaded;
2. expands the case with the PyPI xacro command (xacro_find.py: xacro's own CLI with `$(find)`
   answered from the package folders; no ROS), a whole process, timed;
3. expands it with `robotdesc expand` (default sandbox, one `--package-path` per package
   folder), cold (`--no-cache`) and warm (cache filled by a previous run), whole processes, timed;
4. compares both outputs as canonical XML (comments and whitespace-only text dropped, other
   text with its whitespace runs collapsed, attributes in sorted order) and reports the first difference; robotdesc's internal `_rd_*`
   provenance attributes must not appear in `expand -o` output and are reported if they do;
5. lints the case (`robotdesc lint --format json`): exit code and findings per code;
6. prints a table (text, or markdown with --markdown) and, with --json, writes every result.

A case is: identical, differing (first difference), failed (robotdesc refused or could not
expand; its message), crashed (exit 3 or a Python traceback), or "xacro failed" when the
reference itself cannot expand the case.

Usage:
    python benchmarks/corpus/run_corpus.py [--corpus DIR] [--fetch-root DIR] [--only SUBSTR]
                                           [--repeat N] [--markdown] [--json FILE]
                                           [--extract-only] [--no-bytecode-cache]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from collections import Counter
from pathlib import Path

from lxml import etree

HERE = Path(__file__).resolve().parent
DEFAULT_MANIFEST = HERE / "manifest.toml"
XACRO_LAUNCHER = HERE / "xacro_find.py"
TIMEOUT_S = 300.0
EXIT_INTERNAL = 3


# --------------------------------------------------------------------------- manifest


@dataclasses.dataclass(frozen=True)
class Case:
    name: str
    repository: str  # owner/name
    commit: str
    file: str  # path inside the corpus folder, starting with the repository folder
    args: tuple[str, ...]
    packages: tuple[str, ...]  # package folders inside the corpus folder
    note: str
    loose: bool = False  # run a copy of the top file from a folder with no package.xml above it


def top_file(case: Case, corpus: Path) -> Path:
    """The file both tools are given: the top file, or for a loose case its copy in
    CORPUS/_loose/CASE/ (outside every package: `$(find)` must then crawl the package folders,
    the layout of issue 13's false sandbox refusals)."""
    original = corpus / case.file
    if not case.loose:
        return original
    copy = corpus / "_loose" / case.name / original.name
    copy.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(original, copy)
    return copy


def repo_folder(repository: str) -> str:
    """The folder a repository is extracted to (and the name of its fetch mirror)."""
    return repository.replace("/", "+")


@dataclasses.dataclass(frozen=True)
class Manifest:
    cases: list[Case]
    commits: dict[str, str]  # repository folder (OWNER+NAME) -> commit


def load_manifest(path: Path) -> Manifest:
    data = tomllib.loads(path.read_text())
    cases = [
        Case(name=entry["name"], repository=entry["repository"], commit=entry["commit"],
             file=entry["file"], args=tuple(entry.get("args", ())),
             packages=tuple(entry.get("packages", ())), note=entry.get("note", ""),
             loose=entry.get("loose", False))
        for entry in data["case"]
    ]
    pairs = [(c.repository, c.commit) for c in cases]
    pairs += [(d["repository"], d["commit"]) for d in data.get("dependency", [])]
    commits = one_commit_each(pairs)
    check_folders(cases, commits)
    return Manifest(cases, commits)


def one_commit_each(pairs: list[tuple[str, str]]) -> dict[str, str]:
    """One commit per repository: the corpus holds one tree of each."""
    commits: dict[str, str] = {}
    for repository, commit in pairs:
        if commits.setdefault(repo_folder(repository), commit) != commit:
            raise SystemExit(f"{repository} at two commits in the manifest")
    return commits


def check_folders(cases: list[Case], commits: dict[str, str]) -> None:
    """Every file and package folder lies in a repository the manifest gives a commit for."""
    for case in cases:
        for path in (case.file, *case.packages):
            if path.split("/")[0] not in commits:
                raise SystemExit(f"{case.name}: {path} is in no repository of the manifest")


# --------------------------------------------------------------------------- extraction


def mirror_dir(fetch_root: Path, folder: str) -> Path:
    """The git directory of a fetch snapshot: FETCH_ROOT/OWNER+NAME/repo, a bare repository,
    or the `.git` inside it when the snapshot came as a work-tree-less clone (RethinkRobotics'
    sawyer_robot did)."""
    repo = fetch_root / folder / "repo"
    inner = repo / ".git"
    return inner if inner.is_dir() else repo


def extract(folder: str, commit: str, fetch_root: Path, corpus: Path) -> None:
    """Extract one repository at `commit` from its fetch mirror, unless already there."""
    dest = corpus / folder
    stamp = dest / ".corpus-commit"
    if stamp.is_file() and stamp.read_text().strip() == commit:
        return
    mirror = mirror_dir(fetch_root, folder)
    if not mirror.is_dir():
        source = "github:" + folder.replace("+", "/")
        raise SystemExit(f"no mirror {mirror}: bring it with the fetch tool ({source})")
    shutil.rmtree(dest, ignore_errors=True)
    dest.mkdir(parents=True)
    missing = write_tree(mirror, commit, dest)
    stamp.write_text(commit + "\n")
    note = ""
    if missing:
        note = f" ({len(missing)} large files absent from the snapshot, e.g. {missing[0]})"
    print(f"extracted {folder} at {commit[:12]}{note}", file=sys.stderr)


def tree_entries(mirror: Path, commit: str) -> list[tuple[str, str, str]]:
    """(mode, blob id, path) of every file at `commit`; submodules left out."""
    listing = subprocess.run(["git", f"--git-dir={mirror}", "ls-tree", "-r", "-z", commit],
                             capture_output=True, check=True).stdout.decode()
    entries = []
    for record in filter(None, listing.split("\0")):
        meta, path = record.split("\t", 1)
        mode, kind, blob = meta.split()
        if kind == "blob":
            entries.append((mode, blob, path))
    return entries


def write_tree(mirror: Path, commit: str, dest: Path) -> list[str]:
    """Write the files of `commit` under `dest` (like `git archive`, but a snapshot may lack its
    largest blobs, usually meshes: those are skipped). Returns the paths that were absent."""
    entries = tree_entries(mirror, commit)
    batch = subprocess.Popen(["git", f"--git-dir={mirror}", "cat-file", "--batch"],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    assert batch.stdin and batch.stdout
    missing = []
    for mode, blob, path in entries:
        batch.stdin.write(blob.encode() + b"\n")
        batch.stdin.flush()
        header = batch.stdout.readline().split()
        if header[-1] == b"missing":
            missing.append(path)
            continue
        content = batch.stdout.read(int(header[2]))
        batch.stdout.read(1)  # the newline after each object
        write_entry(dest / path, mode, content)
    batch.stdin.close()
    batch.wait()
    return missing


def write_entry(target: Path, mode: str, content: bytes) -> None:
    target.parent.mkdir(parents=True, exist_ok=True)
    if mode == "120000":
        target.symlink_to(content.decode())
        return
    target.write_bytes(content)
    if mode == "100755":
        target.chmod(0o755)


def extract_all(commits: dict[str, str], fetch_root: Path, corpus: Path) -> None:
    for folder, commit in sorted(commits.items()):
        extract(folder, commit, fetch_root, corpus)


# --------------------------------------------------------------------------- packages


NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")


def package_table(folders: list[Path]) -> dict[str, Path]:
    """Package name -> folder, for every package.xml under the folders (first one found wins)."""
    table: dict[str, Path] = {}
    for root in folders:
        for current, dirs, files in os.walk(root):
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            if "package.xml" in files:
                match = NAME_RE.search(Path(current, "package.xml").read_bytes())
                if match:
                    table.setdefault(match.group(1).decode(), Path(current))
    return table


# --------------------------------------------------------------------------- processes


@dataclasses.dataclass
class Run:
    code: int | None  # None: timed out
    seconds: float
    stderr: str

    @property
    def ok(self) -> bool:
        return self.code == 0

    @property
    def crashed(self) -> bool:
        return self.code == EXIT_INTERNAL or "Traceback (most recent call last)" in self.stderr


def run(command: list[str], env: dict[str, str], cwd: Path) -> Run:
    start = time.perf_counter()
    try:
        done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                              cwd=cwd, timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return Run(None, time.perf_counter() - start, f"timed out after {TIMEOUT_S:.0f} s")
    return Run(done.returncode, time.perf_counter() - start, done.stderr.decode(errors="replace"))


def median_run(command: list[str], env: dict[str, str], cwd: Path, repeat: int) -> Run:
    """Run `repeat` times: the last run's exit code and message, the median time."""
    runs = [run(command, env, cwd) for _ in range(max(repeat, 1))]
    result = runs[-1]
    result.seconds = statistics.median(r.seconds for r in runs)
    return result


def process_env(scratch: Path, bytecode_cache: bool = True) -> dict[str, str]:
    """The environment of every timed process: robotdesc's cache in `scratch`, and (unless told
    not to) compiled bytecode kept in `scratch` too, as a wheel install has it. Without that, a
    PYTHONDONTWRITEBYTECODE=1 environment recompiles robotdesc's modules in every process (the
    installed xacro has its .pyc files), which measures the compiler rather than either tool."""
    env = dict(os.environ, ROBOTDESC_CACHE_DIR=str(scratch / "cache"))
    if bytecode_cache:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(scratch / "pycache")
    return env


def xacro_command(case: Case, corpus: Path, out: Path) -> list[str]:
    table = package_table([corpus / folder for folder in case.packages])
    packages = [arg for name, folder in sorted(table.items())
                for arg in ("--package", f"{name}={folder}")]
    return [sys.executable, str(XACRO_LAUNCHER), *packages, "--", str(top_file(case, corpus)),
            *case.args, "-o", str(out)]


def package_options(case: Case, corpus: Path) -> list[str]:
    return [arg for folder in case.packages for arg in ("--package-path", str(corpus / folder))]


def robotdesc_command(verb: str, case: Case, corpus: Path) -> list[str]:
    return [sys.executable, "-m", "robotdesc", verb, str(top_file(case, corpus)), *case.args,
            *package_options(case, corpus)]


# --------------------------------------------------------------------------- comparison


def canonical(path: Path) -> etree._Element:
    """The document with comments, processing instructions and whitespace-only text dropped,
    and runs of whitespace in other text collapsed to one space: the xacro command prints with
    minidom's pretty printer, which re-indents the text of mixed content (a stray `>` after
    an element), although the document xacro builds holds the same text as robotdesc's."""
    parser = etree.XMLParser(remove_comments=True, remove_pis=True, remove_blank_text=True,
                             resolve_entities=False, huge_tree=True)
    root = etree.parse(str(path), parser).getroot()
    for element in root.iter():
        element.text = " ".join(element.text.split()) or None if element.text else None
        element.tail = " ".join(element.tail.split()) or None if element.tail else None
    return root


def where(element: etree._Element) -> str:
    """A readable path to an element: robot/link[name=base]/visual[2]."""
    steps = []
    while element is not None:
        name = element.get("name")
        label = etree.QName(element).localname if isinstance(element.tag, str) else "?"
        parent = element.getparent()
        if name is not None:
            label += f"[name={name}]"
        elif parent is not None:
            same = [child for child in parent if child.tag == element.tag]
            if len(same) > 1:
                label += f"[{same.index(element) + 1}]"
        steps.append(label)
        element = parent
    return "/".join(reversed(steps))


def first_difference(a: etree._Element, b: etree._Element) -> str | None:
    """The first difference between two canonical trees (xacro's `a`, robotdesc's `b`)."""
    if a.tag != b.tag:
        return f"{where(a)}: element <{a.tag}> (xacro) vs <{b.tag}> (robotdesc)"
    if dict(sorted(a.attrib.items())) != dict(sorted(b.attrib.items())):
        keys = sorted(set(a.attrib) | set(b.attrib))
        key = next(k for k in keys if a.get(k) != b.get(k))
        return f"{where(a)}: @{key} {a.get(key)!r} (xacro) vs {b.get(key)!r} (robotdesc)"
    for attr in ("text", "tail"):
        if getattr(a, attr) != getattr(b, attr):
            ours, theirs = getattr(a, attr), getattr(b, attr)
            return f"{where(a)}: {attr} {ours!r} (xacro) vs {theirs!r} (robotdesc)"
    for child_a, child_b in zip(a, b):
        found = first_difference(child_a, child_b)
        if found:
            return found
    if len(a) != len(b):
        longer, side = (a, "xacro") if len(a) > len(b) else (b, "robotdesc")
        extra = longer[min(len(a), len(b))]
        return (f"{where(a)}: {len(a)} children (xacro) vs {len(b)} (robotdesc); "
                f"first extra in {side}: {where(extra)}")
    return None


def provenance_leak(path: Path) -> str | None:
    """robotdesc's internal `_rd_*` attributes in its output, if any."""
    match = re.search(rb"\s(_rd_[A-Za-z0-9_]*)=", path.read_bytes())
    return match.group(1).decode() if match else None


# --------------------------------------------------------------------------- lint


def lint_case(case: Case, corpus: Path,
              env: dict[str, str]) -> tuple[int | None, dict[str, int], str]:
    """Exit code, findings per code, and the first failure message of `robotdesc lint`."""
    command = robotdesc_command("lint", case, corpus) + ["--format", "json"]
    try:
        done = subprocess.run(command, capture_output=True, env=env, cwd=corpus, timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return None, {}, "timed out"
    try:
        report = json.loads(done.stdout)
    except ValueError:
        return done.returncode, {}, first_line(done.stderr.decode(errors="replace"))
    counts = Counter(d["code"] for d in report.get("diagnostics", []))
    failures = report.get("failures", [])
    return done.returncode, dict(sorted(counts.items())), failures[0]["message"] if failures else ""


# --------------------------------------------------------------------------- one case


@dataclasses.dataclass
class Result:
    case: str
    repository: str
    status: str  # identical | differing | failed | crashed | xacro failed
    detail: str
    xacro_s: float
    cold_s: float | None
    warm_s: float | None
    lint_exit: int | None
    findings: dict[str, int]
    lint_failure: str
    leak: str | None


def first_line(text: str) -> str:
    """The most telling line of an error output: the first line that says error, else the last."""
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    for line in lines:
        if "error" in line.lower() or "refuses" in line:
            return line
    return lines[-1] if lines else ""


def compare_outputs(xacro_run: Run, cold: Run, xacro_out: Path, ours_out: Path) -> tuple[str, str]:
    if cold.crashed:
        return "crashed", first_line(cold.stderr)
    if not xacro_run.ok:
        detail = first_line(xacro_run.stderr)
        if cold.ok:
            return "xacro failed", f"robotdesc expanded it; xacro: {detail}"
        return "xacro failed", f"both failed; xacro: {detail}; robotdesc: {first_line(cold.stderr)}"
    if not cold.ok:
        return "failed", first_line(cold.stderr)
    try:
        ours = canonical(ours_out)
    except (OSError, etree.XMLSyntaxError) as error:
        return "differing", f"robotdesc's output does not parse: {error}"
    difference = first_difference(canonical(xacro_out), ours)
    return ("differing", difference) if difference else ("identical", "")


def warm_up(xacro_cmd: list[str], expand: list[str], env: dict[str, str], cwd: Path) -> None:
    """One untimed run of each tool, so that the first case does not pay for writing bytecode
    and the disk cache holds the files (cold means: no robotdesc expansion cache, not a cold OS)."""
    run(xacro_cmd, env, cwd)
    run(expand + ["--no-cache"], env, cwd)


def measure(case: Case, corpus: Path, env: dict[str, str], out_dir: Path, repeat: int) -> Result:
    xacro_out = out_dir / f"{case.name}.xacro.urdf"
    ours_out = out_dir / f"{case.name}.robotdesc.urdf"
    for stale in (xacro_out, ours_out):
        stale.unlink(missing_ok=True)
    xacro_cmd = xacro_command(case, corpus, xacro_out)
    expand = robotdesc_command("expand", case, corpus) + ["-o", str(ours_out)]
    warm_up(xacro_cmd, expand, env, corpus)
    xacro_run = median_run(xacro_cmd, env, corpus, repeat)
    cold = median_run(expand + ["--no-cache"], env, corpus, repeat)
    warm = None
    if cold.ok:
        run(expand, env, corpus)  # fill the cache
        warm = median_run(expand, env, corpus, repeat)
    status, detail = compare_outputs(xacro_run, cold, xacro_out, ours_out)
    lint_exit, findings, lint_failure = lint_case(case, corpus, env)
    return Result(case=case.name, repository=case.repository, status=status, detail=detail,
                  xacro_s=xacro_run.seconds, cold_s=cold.seconds if cold.ok else None,
                  warm_s=warm.seconds if warm and warm.ok else None, lint_exit=lint_exit,
                  findings=findings, lint_failure=lint_failure,
                  leak=provenance_leak(ours_out) if cold.ok and ours_out.is_file() else None)


# --------------------------------------------------------------------------- reports


STATUSES = ("identical", "differing", "failed", "crashed", "xacro failed")


def seconds(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def findings_text(result: Result) -> str:
    text = " ".join(f"{code}x{count}" for code, count in result.findings.items()) or "none"
    return text + (f" (not checked: {result.lint_failure})" if result.lint_failure else "")


def status_text(result: Result) -> str:
    text = result.status + (f": {result.detail}" if result.detail else "")
    return text + (f" [output has {result.leak}]" if result.leak else "")


def print_text_table(results: list[Result]) -> None:
    print(f"{'case':34s} {'xacro':>6s} {'cold':>6s} {'warm':>6s} {'lint':>4s}  result / findings")
    for r in results:
        times = " ".join(f"{seconds(s):>6s}" for s in (r.xacro_s, r.cold_s, r.warm_s))
        print(f"{r.case:34s} {times} {str(r.lint_exit):>4s}  {status_text(r)}")
        print(f"{'':34s} {'':27s}  findings: {findings_text(r)}")


def markdown_cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def print_markdown_table(results: list[Result]) -> None:
    print("| case | repository | result | xacro s | cold s | warm s | lint exit | findings |")
    print("|---|---|---|---|---|---|---|---|")
    for r in results:
        cells = [r.case, r.repository, markdown_cell(status_text(r)), seconds(r.xacro_s),
                 seconds(r.cold_s), seconds(r.warm_s), str(r.lint_exit),
                 markdown_cell(findings_text(r))]
        print("| " + " | ".join(cells) + " |")


def speed_summary(results: list[Result]) -> list[str]:
    """Medians over the cases robotdesc expanded, and the per-case ratios' medians (item 9)."""
    timed = [r for r in results
             if r.cold_s is not None and r.warm_s is not None and r.status != "xacro failed"]
    if not timed:
        return ["speed: no case expanded by both"]
    xacro = statistics.median(r.xacro_s for r in timed)
    cold = statistics.median(r.cold_s for r in timed)
    warm = statistics.median(r.warm_s for r in timed)
    cold_ratio = statistics.median(r.cold_s / r.xacro_s for r in timed)
    warm_ratio = statistics.median(r.warm_s / r.xacro_s for r in timed)
    return [
        f"speed over {len(timed)} cases (whole processes, one run each; median seconds, "
        "median of per-case ratios; benchmarks/bench_corpus.py repeats them):",
        f"  xacro CLI                  {xacro:6.3f} s",
        f"  robotdesc expand, cold     {cold:6.3f} s   ratio {cold_ratio:5.2f}  (aim <= 1.50)",
        f"  robotdesc expand, warm     {warm:6.3f} s   ratio {warm_ratio:5.2f}  (aim <= 0.25)",
    ]


def summary(results: list[Result]) -> list[str]:
    counts = Counter(r.status for r in results)
    repos = len({r.repository for r in results})
    lines = [f"{len(results)} cases from {repos} repositories: "
             + ", ".join(f"{counts.get(s, 0)} {s}" for s in STATUSES)]
    leaks = [r.case for r in results if r.leak]
    lines.append(f"_rd_* attributes in expand output: {', '.join(leaks) if leaks else 'none'}")
    lint = Counter(r.lint_exit for r in results)
    exits = ", ".join(f"{code}: {n}" for code, n in sorted(lint.items(), key=str))
    lines.append(f"lint exit codes: {exits}")
    return lines + speed_summary(results)


# --------------------------------------------------------------------------- main


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--manifest", type=Path, default=DEFAULT_MANIFEST)
    parser.add_argument("--corpus", type=Path, default=Path("/work/corpus"),
                        help="where the repositories are extracted (default: /work/corpus)")
    parser.add_argument("--fetch-root", type=Path, default=Path("/work/.mirror"),
                        help="the fetch mirrors, OWNER+NAME/repo (default: /work/.mirror)")
    parser.add_argument("--only", action="append", default=[],
                        help="cases whose name contains this (repeatable)")
    parser.add_argument("--repeat", type=int, default=1, help="time each command N times (median)")
    parser.add_argument("--markdown", action="store_true", help="print the table as markdown")
    parser.add_argument("--json", type=Path, help="write every result to this JSON file")
    parser.add_argument("--no-bytecode-cache", action="store_true",
                        help="keep the environment's PYTHONDONTWRITEBYTECODE (see process_env)")
    parser.add_argument("--extract-only", action="store_true", help="only extract the corpus")
    return parser.parse_args(argv)


def select(cases: list[Case], only: list[str]) -> list[Case]:
    return [c for c in cases if not only or any(part in c.name for part in only)]


def run_corpus(options: argparse.Namespace) -> list[Result]:
    manifest = load_manifest(options.manifest)
    corpus = options.corpus.resolve()
    extract_all(manifest.commits, options.fetch_root, corpus)
    if options.extract_only:
        return []
    out_dir = corpus / "_out"
    out_dir.mkdir(exist_ok=True)
    results = []
    with tempfile.TemporaryDirectory(prefix="robotdesc-corpus-") as scratch:
        env = process_env(Path(scratch), not options.no_bytecode_cache)
        for case in select(manifest.cases, options.only):
            result = measure(case, corpus, env, out_dir, options.repeat)
            print(f"{case.name}: {status_text(result)}", file=sys.stderr)
            results.append(result)
    return results


def main(argv: list[str] | None = None) -> None:
    options = parse_args(argv)
    results = run_corpus(options)
    if not results:
        return
    (print_markdown_table if options.markdown else print_text_table)(results)
    print()
    print("\n".join(summary(results)))
    if options.json:
        options.json.write_text(json.dumps([dataclasses.asdict(r) for r in results], indent=1))


if __name__ == "__main__":
    main()
