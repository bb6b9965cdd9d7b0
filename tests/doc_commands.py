#!/usr/bin/env python3
"""Runs the command blocks of README.md and docs/*.md as a newcomer would: in order, per
document, in a fresh copy of the repository's files (a temporary folder per document), with the
build's `rins` on PATH. Fails naming the document, the block's line, the command and its stderr
tail when a block fails, or when an output block the document marks no longer matches.

Python 3.11 standard library only.

Which fenced blocks run:
  ```sh / ```bash / ```shell   run by bash, each command traced so a failure names its line;
  ```python                     run by the doc Python (--python, $RINS_DOC_PYTHON or python3);
  any other info string         listed as "not a command" (TOML, text, transcripts, diagrams).

Markers: HTML comments on the lines directly above a fence (several may be stacked):
  <!-- doc-test: skip (REASON) -->         not run; listed with the reason (the reason is required).
  <!-- doc-test: needs FEATURE -->          run only when the feature is available, else listed as
                                            skipped naming it. Features: rerun (the rins binary was
                                            built with --features rerun; probed by recording one
                                            short run, or forced by RINS_DOC_RERUN=0/1).
  <!-- doc-test: replace "OLD" "NEW" -->    literal substitution before running (a short duration
                                            for a long run); OLD must occur in the block.
  <!-- doc-test: env NAME=VALUE -->         an environment variable for the block ($VAR expands
                                            from the test's environment).
  <!-- doc-test: timeout SECONDS -->        the block's time limit (default 600 s).
  <!-- doc-test: exit STATUS -->            the block must end with this exit status (a command
                                            shown failing: its last command; default 0).
  <!-- doc-test: output -->                 on an output block: every line of it must occur in the
                                            output (stdout + stderr) of the command block just
                                            before it, with runs of spaces counted as one; an
                                            ellipsis (`…` or `...`) stands for elided text, the
                                            pieces around it must occur. So each number is checked
                                            to the digits it is printed with.

Usage: tests/doc_commands.py [--bin DIR] [--python PY] [--keep] [--keep-going] [--list] [--self-test] [DOC ...]
Exit status 0 when every block that runs passes, 1 otherwise, 2 on a malformed marker.
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SHELL_LANGS = {"sh", "bash", "shell"}
PYTHON_LANGS = {"python", "py", "python3"}
DEFAULT_TIMEOUT_S = 600
FEATURES = ("rerun",)
MARKER = re.compile(r"^\s*<!--\s*doc-test:\s*(.*?)\s*-->\s*$")


class MarkerError(Exception):
    """A malformed doc-test marker: the document must be fixed, not the block skipped."""


@dataclass
class Block:
    doc: str
    line: int  # 1-based line of the opening fence
    lang: str
    text: str
    skip: str | None = None
    needs: list[str] = field(default_factory=list)
    replace: list[tuple[str, str]] = field(default_factory=list)
    env: dict[str, str] = field(default_factory=dict)
    timeout_s: float = DEFAULT_TIMEOUT_S
    output_check: bool = False
    expect_rc: int = 0
    status: str = ""
    seconds: float = 0.0

    @property
    def kind(self) -> str:
        if self.output_check:
            return "output"
        if self.lang in SHELL_LANGS:
            return "sh"
        if self.lang in PYTHON_LANGS:
            return "python"
        return "other"


def parse_marker(body: str, block: Block, where: str) -> None:
    """Applies one marker's text (after `doc-test:`) to the block."""
    m = re.fullmatch(r"skip\s*\((.+)\)", body)
    if m:
        block.skip = m.group(1).strip()
        return
    if body.startswith("skip"):
        raise MarkerError(f"{where}: `skip` needs a reason in parentheses: skip (REASON)")
    m = re.fullmatch(r"needs\s+(\S+)", body)
    if m:
        if m.group(1) not in FEATURES:
            raise MarkerError(f"{where}: unknown feature {m.group(1)!r}; expected one of {FEATURES}")
        block.needs.append(m.group(1))
        return
    m = re.fullmatch(r'replace\s+"((?:[^"\\]|\\.)*)"\s+"((?:[^"\\]|\\.)*)"', body)
    if m:
        old, new = (s.replace('\\"', '"') for s in m.groups())
        if not old:
            raise MarkerError(f"{where}: `replace` with an empty OLD")
        block.replace.append((old, new))
        return
    m = re.fullmatch(r"env\s+([A-Za-z_][A-Za-z0-9_]*)=(.*)", body)
    if m:
        block.env[m.group(1)] = m.group(2)
        return
    m = re.fullmatch(r"timeout\s+(\d+(?:\.\d+)?)", body)
    if m:
        block.timeout_s = float(m.group(1))
        return
    if body == "output":
        block.output_check = True
        return
    m = re.fullmatch(r"exit\s+(\d+)", body)
    if m:
        block.expect_rc = int(m.group(1))
        return
    raise MarkerError(
        f"{where}: unknown marker {body!r}; expected skip (REASON), needs FEATURE, "
        f'replace "OLD" "NEW", env NAME=VALUE, timeout SECONDS, exit STATUS or output'
    )


def extract(doc: Path) -> list[Block]:
    """The fenced blocks of one Markdown file with the markers directly above each."""
    rel = display(doc)
    lines = doc.read_text(encoding="utf-8").splitlines()
    blocks: list[Block] = []
    i = 0
    while i < len(lines):
        m = re.match(r"^(\s*)(```+|~~~+)\s*([^\s`]*)", lines[i])
        if not m:
            i += 1
            continue
        indent, fence, lang = m.group(1), m.group(2), m.group(3).lower()
        start = i
        body = []
        i += 1
        while i < len(lines) and not lines[i].strip().startswith(fence):
            body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i])
            i += 1
        if i >= len(lines):
            raise MarkerError(f"{rel}:{start + 1}: unclosed code fence")
        i += 1
        block = Block(rel, start + 1, lang, "\n".join(body) + "\n")
        markers = []
        j = start - 1
        while j >= 0 and MARKER.match(lines[j]):
            markers.append((j, MARKER.match(lines[j]).group(1)))
            j -= 1
        for j, text in reversed(markers):
            parse_marker(text, block, f"{rel}:{j + 1}")
        blocks.append(block)
    # A doc-test comment not directly above a fence would be a silent no-op: refuse it.
    used = set()
    for b in blocks:
        j = b.line - 2
        while j >= 0 and MARKER.match(lines[j]):
            used.add(j)
            j -= 1
    for n, line in enumerate(lines):
        if "doc-test:" in line and n not in used and MARKER.match(line):
            raise MarkerError(f"{rel}:{n + 1}: a doc-test marker must sit directly above a code fence")
    return blocks


def display(doc: Path) -> str:
    """The document's path relative to the repository when it is inside it."""
    try:
        return str(doc.relative_to(ROOT))
    except ValueError:
        return str(doc)


def logical_commands(text: str) -> list[tuple[int, str]]:
    """(0-based line in the block, command) for each top-level command of a shell block:
    continuation lines joined, comments and blank lines dropped, here-documents kept whole."""
    out: list[tuple[int, str]] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        first = i
        cmd = lines[i]
        while cmd.rstrip().endswith("\\") and i + 1 < len(lines):
            i += 1
            cmd += "\n" + lines[i]
        heredoc = re.search(r"<<-?\s*['\"]?([A-Za-z_][A-Za-z0-9_]*)['\"]?", cmd)
        if heredoc and not cmd.lstrip().startswith("#"):
            while i + 1 < len(lines):
                i += 1
                cmd += "\n" + lines[i]
                if lines[i].strip() == heredoc.group(1):
                    break
        i += 1
        if cmd.strip() and not cmd.lstrip().startswith("#"):
            out.append((first, cmd))
    return out


def shell_script(block: Block, text: str, mark_file: str) -> str:
    """The block as a bash script that records the line of each command before running it."""
    parts = ["set -e -o pipefail"]
    for offset, cmd in logical_commands(text):
        line = block.line + 1 + offset
        parts.append(f"printf '%s\\n' {line} > {shlex.quote(mark_file)}")
        parts.append(cmd)
    return "\n".join(parts) + "\n"


def copy_repository(dest: Path) -> None:
    """The repository's tracked files as they are in the working tree: a fresh clone without
    the build outputs (target/, out/, built FMUs) a used checkout accumulates."""
    r = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True)
    if r.returncode == 0:
        files = r.stdout.decode().split("\0")
    else:  # not a git checkout (an unpacked archive): every file but the ignored build outputs
        skip = {".git", "target", "out", ".venv", "__pycache__"}
        files = [str(p.relative_to(ROOT)) for p in ROOT.rglob("*")
                 if p.is_file() and not skip.intersection(p.relative_to(ROOT).parts)
                 and p.suffix != ".fmu"]
    for rel in files:
        if not rel:
            continue
        src = ROOT / rel
        if not src.is_file():  # deleted in the working tree
            continue
        target = dest / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, target)


def probe_rerun(rins: str, work: Path) -> bool:
    """True when the rins binary records Rerun files (built with --features rerun)."""
    forced = os.environ.get("RINS_DOC_RERUN")
    if forced in ("0", "1"):
        return forced == "1"
    r = subprocess.run(
        [rins, "run", "builtin:calibration-z-up", "--duration-s", "1", "--out", str(work / "probe"),
         "--rerun", f"save:{work / 'probe.rrd'}"],
        capture_output=True, timeout=120,
    )
    return r.returncode == 0


def tail(text: str, n: int = 25) -> str:
    lines = text.rstrip().splitlines()
    return "\n".join("    " + l for l in lines[-n:])


NUMBER = re.compile(r"[-+−]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?")


def skeleton(s: str) -> str:
    """A line with its numbers replaced by '#' and its white space normalised: two lines
    with the same skeleton say the same thing with other figures."""
    return normalise(NUMBER.sub("#", s))


def normalise(s: str) -> str:
    return re.sub(r"\s+", " ", s).strip()


def shows(have: str, piece: str) -> bool:
    """True when `piece` occurs in `have` and a number at either end of it is not part of a
    longer one there: "got 9" is not shown by "got 95", nor "0.71" by "10.71" or "0.715"."""
    pattern = re.escape(piece)
    if re.match(r"[-+]?\.?\d", piece):
        pattern = r"(?<![-\d.])" + pattern
    if re.search(r"\d$", piece):
        pattern += r"(?!\d|\.\d)"
    return re.search(pattern, have) is not None


class Runner:
    def __init__(self, bindir: Path, python: str, keep: bool, keep_going: bool = False,
                 update: bool = False):
        self.keep_going = keep_going
        self.update = update
        # (document, 0-based line, old text, new text) of the output lines --update rewrites.
        self.updates: list[tuple[str, int, str, str]] = []
        self.bindir = bindir
        self.python = python
        self.keep = keep
        self.failures: list[str] = []
        self.features: dict[str, bool] = {}

    def env(self, block: Block, work: Path) -> dict[str, str]:
        env = dict(os.environ)
        env["PATH"] = f"{self.bindir}{os.pathsep}{env.get('PATH', '')}"
        env["RINS_DOC_TEST"] = "1"
        env["HOME"] = env.get("HOME", str(work))
        for k, v in block.env.items():
            env[k] = os.path.expandvars(v)
        return env

    def run_process(self, argv, block, work, log_dir, n):
        """Runs argv in its own process group (so a backgrounded server is ended with it)."""
        out_path, err_path = log_dir / f"{n}.out", log_dir / f"{n}.err"
        with open(out_path, "wb") as out, open(err_path, "wb") as err:
            p = subprocess.Popen(argv, cwd=work, env=self.env(block, work), stdout=out, stderr=err,
                                 stdin=subprocess.DEVNULL, start_new_session=True)
            timed_out = False
            try:
                p.wait(timeout=block.timeout_s)
            except subprocess.TimeoutExpired:
                timed_out = True
            finally:
                try:
                    os.killpg(p.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                p.wait()
        rc = None if timed_out else p.returncode
        return rc, out_path.read_text(errors="replace"), err_path.read_text(errors="replace")

    def run_doc(self, doc: Path, blocks: list[Block]) -> None:
        base = Path(tempfile.mkdtemp(prefix="rins-doc-"))
        work, log_dir = base / "repo", base / "logs"
        log_dir.mkdir()
        work.mkdir()
        copy_repository(work)
        last_output: tuple[Block, str] | None = None
        broken = None  # a failed block stops the document: later blocks depend on it
        last_failed = None  # with --keep-going: the command block before an output block failed
        for n, b in enumerate(blocks):
            if b.kind == "other":
                b.status = f"not a command ({b.lang or 'no language'})"
                continue
            if b.kind == "output":
                if broken or last_failed:
                    b.status = f"not checked: block at line {broken or last_failed} failed"
                elif last_output is None:
                    self.fail(b, "an output block with no command block before it")
                else:
                    self.check_output(b, *last_output)
                continue
            if b.skip:
                b.status = f"skipped: {b.skip}"
                continue
            missing = [f for f in b.needs if not self.feature(f, base)]
            if missing:
                b.status = f"skipped: needs {', '.join(missing)}, which this build lacks"
                continue
            if broken:
                b.status = f"not run: block at line {broken} failed"
                continue
            text = b.text
            for old, new in b.replace:
                if old not in text:
                    self.fail(b, f'replace marker: "{old}" does not occur in the block')
                    break
                text = text.replace(old, new)
            else:
                t0 = time.monotonic()
                ok, output = self.run_block(b, text, work, log_dir, n)
                b.seconds = time.monotonic() - t0
                if ok:
                    b.status = "ran" + (f" (with {len(b.replace)} substitution(s))" if b.replace else "")
                    last_output, last_failed = (b, output), None
                    continue
            last_failed = b.line
            if not self.keep_going:
                broken = b.line
        failed = any(b.status == "FAILED" for b in blocks)
        if not self.keep and not failed:
            shutil.rmtree(base, ignore_errors=True)
        elif failed:
            print(f"  (work folder kept: {base})", file=sys.stderr)

    def feature(self, name: str, base: Path) -> bool:
        if name not in self.features:
            self.features[name] = probe_rerun(str(self.bindir / "rins"), base)
        return self.features[name]

    def run_block(self, b: Block, text: str, work: Path, log_dir: Path, n: int) -> tuple[bool, str]:
        if b.kind == "sh":
            mark = log_dir / f"{n}.line"
            script = log_dir / f"{n}.sh"
            script.write_text(shell_script(b, text, str(mark)))
            rc, out, err = self.run_process(["bash", str(script)], b, work, log_dir, n)
            line = int(mark.read_text().strip()) if mark.exists() and mark.read_text().strip() else b.line
            last = b.line + 1 + logical_commands(text)[-1][0]
            # A block shown failing must fail in its last command, not earlier.
            if rc == b.expect_rc and (rc == 0 or line == last):
                return True, out + err
            cmd = next((c for o, c in logical_commands(text) if b.line + 1 + o == line), "?")
        else:
            script = log_dir / f"{n}.py"
            script.write_text(text)
            rc, out, err = self.run_process([self.python, str(script)], b, work, log_dir, n)
            if rc == b.expect_rc:
                return True, out + err
            lines = [int(x) for x in re.findall(rf'File "{re.escape(str(script))}", line (\d+)', err)]
            if lines:  # the traceback's last frame in the block
                line = b.line + lines[-1]
                cmd = text.splitlines()[lines[-1] - 1] if lines[-1] <= len(text.splitlines()) else "?"
            else:  # no traceback (SystemExit, a crash in native code): the block as a whole
                line, cmd = b.line, "(the block: no traceback names a line)"
        if rc is None:
            why = f"timed out after {b.timeout_s:.0f} s"
        elif rc == b.expect_rc:
            why = f"exit status {rc} before the block's last command, which is the one shown failing"
        else:
            why = f"exit status {rc}" + (f", expected {b.expect_rc}" if b.expect_rc else "")
        self.fail(b, f"line {line}: {why}\n  command: {cmd.strip()}\n  stderr (tail):\n{tail(err)}"
                     + (f"\n  stdout (tail):\n{tail(out, 10)}" if out.strip() else ""), line)
        return False, out + err

    def check_output(self, b: Block, cmd_block: Block, output: str) -> None:
        have = normalise(output)
        # An ellipsis inside or at the end of a line stands for elided text: each piece around
        # it must occur.
        missing = [l for l in b.text.splitlines()
                   if any(p and not shows(have, p)
                          for p in (normalise(x) for x in re.split(r"\.\.\.|…", l)))]
        updated = 0
        if missing and self.update:
            before = len(self.updates)
            missing = self.propose_updates(b, missing, output)
            updated = len(self.updates) - before
        if missing:
            self.fail(b, f"output of the block at line {cmd_block.line} no longer shows:\n"
                         + "\n".join(f"    {l}" for l in missing)
                         + f"\n  its output (tail):\n{tail(output, 15)}")
        else:
            b.status = f"checked: {sum(1 for l in b.text.splitlines() if l.strip())} line(s) against line {cmd_block.line}" + (
                f", {updated} updated" if updated else "")

    def propose_updates(self, b: Block, missing: list[str], output: str) -> list[str]:
        """With --update: each missing line whose text, numbers aside, is one output line's
        becomes that line (kept in `self.updates` for the document); returns the lines that
        have no such counterpart (changed wording, or an elided line), which stay failures."""
        lines = b.text.splitlines()
        outs = output.splitlines()
        left = []
        for line in missing:
            if re.search(r"\.\.\.|…", line):
                left.append(line)
                continue
            want = skeleton(line)
            match = [o for o in outs if skeleton(o) == want]
            if len(match) != 1:
                left.append(line)
                continue
            # Keep the document's indentation of the line.
            indent = line[: len(line) - len(line.lstrip())]
            new = indent + match[0].strip()
            self.updates.append((b.doc, b.line + lines.index(line), line, new))
        return left

    def fail(self, b: Block, message: str, line: int | None = None) -> None:
        b.status = "FAILED"
        text = f"{b.doc}:{line or b.line}: block at line {b.line} ({b.kind}): {message}"
        self.failures.append(text)
        print(f"FAIL {text}", file=sys.stderr, flush=True)


SELF_TEST_DOC = """\
```sh
echo one
rins run nope.toml --out x \\
   --duration-s 5
echo never
```

<!-- doc-test: output -->
```
never
```

<!-- doc-test: exit 1 -->
```sh
printf '[site]\\nlat_deg = 95\\n' > my.toml
rins run my.toml
```

<!-- doc-test: output -->
```
line 2, column 11: site.lat_deg: expected a number in [-89, 89], got 95
```

<!-- doc-test: output -->
```
line 2, column 11: site.lat_deg: expected a number in [-89, 89], got 9
```

<!-- doc-test: replace "--days 7" "--days 0.1" -->
```sh
echo no such text
```

<!-- doc-test: exit 1 -->
```sh
false
echo the block is shown failing here
```

<!-- doc-test: skip (a reason) -->
```sh
false
```

```python
print("ok")
1/0
```

<!-- doc-test: timeout 1 -->
```sh
sleep 30
```

```toml
a = 1
```
"""

SELF_TEST_EXPECT = [  # (block line, status prefix, text the failure message must hold)
    (1, "FAILED", "line 3: exit status 1"),
    (9, "not checked", ""),
    (14, "ran", ""),
    (20, "checked", ""),
    (25, "FAILED", "got 9"),
    (30, "FAILED", '"--days 7" does not occur'),
    (35, "FAILED", "before the block's last command"),
    (41, "skipped: a reason", ""),
    (45, "FAILED", "line 47: exit status 1"),
    (51, "FAILED", "timed out after 1 s"),
    (55, "not a command (toml)", ""),
]


def self_test(bindir: Path) -> int:
    """Runs a document of known faults and checks each is caught and named as it should be."""
    with tempfile.TemporaryDirectory() as d:
        doc = Path(d) / "self-test.md"
        doc.write_text(SELF_TEST_DOC)
        blocks = extract(doc)
        runner = Runner(bindir, sys.executable, keep=False, keep_going=True)
        import contextlib, io
        with contextlib.redirect_stderr(io.StringIO()):
            runner.run_doc(doc, blocks)
    by_line = {b.line: b for b in blocks}
    bad = []
    for line, status, text in SELF_TEST_EXPECT:
        b = by_line.get(line)
        if b is None or not b.status.startswith(status):
            bad.append(f"block at line {line}: status {b.status if b else 'missing'!r}, expected {status!r}")
        elif text and not any(f"block at line {line} " in f and text in f for f in runner.failures):
            bad.append(f"block at line {line}: no failure message holding {text!r}")
    if len(blocks) != len(SELF_TEST_EXPECT):
        bad.append(f"{len(blocks)} blocks extracted, expected {len(SELF_TEST_EXPECT)}")
    # --update: the stale "got 9" line (block at line 25) is rewritten from the output ("got
    # 95"), and nothing else is touched.
    with tempfile.TemporaryDirectory() as d:
        doc = Path(d) / "self-test.md"
        doc.write_text(SELF_TEST_DOC)
        runner = Runner(bindir, sys.executable, keep=False, keep_going=True, update=True)
        with contextlib.redirect_stderr(io.StringIO()):
            runner.run_doc(doc, extract(doc))
    want = [(doc.name, 25, "line 2, column 11: site.lat_deg: expected a number in [-89, 89], got 9",
             "line 2, column 11: site.lat_deg: expected a number in [-89, 89], got 95")]
    got = [(Path(u[0]).name, *u[1:]) for u in runner.updates]
    if got != want:
        bad.append(f"--update proposed {got}, expected {want}")
    for m in bad:
        print(f"doc-test self-test: {m}", file=sys.stderr)
    print(f"doc-test self-test: {len(SELF_TEST_EXPECT) + 1 - len(bad)} of {len(SELF_TEST_EXPECT) + 1} checks passed")
    return 1 if bad else 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", help="folder of the built rins (default: the folder of `rins` on PATH)")
    ap.add_argument("--python", default=os.environ.get("RINS_DOC_PYTHON", "python3"),
                    help="interpreter for ```python blocks (default: $RINS_DOC_PYTHON or python3)")
    ap.add_argument("--keep", action="store_true", help="keep the temporary folders")
    ap.add_argument("--keep-going", action="store_true",
                    help="run a document's later blocks after one fails (they may fail for that reason)")
    ap.add_argument("--list", action="store_true", help="list the blocks and their markers, run nothing")
    ap.add_argument("--self-test", action="store_true",
                    help="run a built-in document of known faults and check that each is caught")
    ap.add_argument("--update", action="store_true",
                    help="rewrite an output block's line whose figures changed (same text, other "
                         "numbers) from the current output, instead of failing; lines whose "
                         "wording changed still fail (docs/regenerate.sh)")
    ap.add_argument("docs", nargs="*", help="documents relative to the repository (default: all)")
    args = ap.parse_args()

    docs = [(ROOT / d).resolve() for d in args.docs] if args.docs else [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    try:
        per_doc = [(d, extract(d)) for d in docs]
    except MarkerError as e:
        print(f"doc-test: {e}", file=sys.stderr)
        return 2

    if args.list:
        for d, blocks in per_doc:
            for b in blocks:
                marks = ([f"skip ({b.skip})"] if b.skip else []) + [f"needs {f}" for f in b.needs] + \
                        [f'replace "{o}" "{n}"' for o, n in b.replace] + [f"env {k}" for k in b.env]
                print(f"{b.doc}:{b.line}\t{b.kind}\t{'; '.join(marks)}")
        return 0

    rins = shutil.which("rins") if not args.bin else str(Path(args.bin) / "rins")
    if not rins or not os.access(rins, os.X_OK):
        print("doc-test: no rins binary (pass --bin DIR or put it on PATH)", file=sys.stderr)
        return 2
    if args.self_test:
        return self_test(Path(rins).resolve().parent)
    runner = Runner(Path(rins).resolve().parent, args.python, args.keep, args.keep_going, args.update)
    t0 = time.monotonic()
    for d, blocks in per_doc:
        print(f"== {display(d)}" + ("" if blocks else " (no code blocks)"), flush=True)
        if blocks:
            runner.run_doc(d, blocks)
        for b in blocks:
            took = f" [{b.seconds:.1f} s]" if b.seconds else ""
            print(f"  {b.doc}:{b.line:<4} {b.kind:<7} {b.status}{took}", flush=True)
    counts: dict[str, int] = {}
    for _, blocks in per_doc:
        for b in blocks:
            key = next((k for k in ("not a command", "not run", "not checked") if b.status.startswith(k)),
                       b.status.split(" ")[0].rstrip(":"))
            counts[key] = counts.get(key, 0) + 1
    if runner.updates:
        by_doc: dict[str, list[tuple[int, str, str]]] = {}
        for doc, n, old, new in runner.updates:
            by_doc.setdefault(doc, []).append((n, old, new))
        for doc, changes in by_doc.items():
            path = ROOT / doc
            lines = path.read_text(encoding="utf-8").split("\n")
            for n, old, new in changes:
                # The body line as extracted, after the fence's own indentation.
                assert lines[n].endswith(old), (doc, n + 1, lines[n], old)
                lines[n] = lines[n][: len(lines[n]) - len(old)] + new
                print(f"doc-test: updated {doc}:{n + 1}\n    - {old.strip()}\n    + {new.strip()}")
            path.write_text("\n".join(lines), encoding="utf-8")
    summary = ", ".join(f"{v} {k}" for k, v in sorted(counts.items()))
    print(f"doc-test: {summary} in {time.monotonic() - t0:.0f} s")
    if runner.failures:
        print(f"doc-test: {len(runner.failures)} failure(s):", file=sys.stderr)
        for f in runner.failures:
            print(f"  {f.splitlines()[0]}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
