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
  <!-- doc-test: name NAME -->              names a command block for `quotes from NAME`.

Prose quotes: a marker on the line directly above a paragraph, a list item or a table (indented
like it; nothing between them) checks the figures that text quotes from a command's output:
  <!-- doc-test: quotes [from NAME] N1 N2 ... ["PHRASE" ...] -->
Each listed number must occur in the text below the marker (with its sign as printed there;
`−` counts as `-`), and must be shown by the output (stdout + stderr) of the command block just
before the text, or of the block named NAME, to its printed digits: some number x of that output,
printed with at least as many decimals, lies within half a unit of the quote's last digit
(`1.797` is shown by 1.797, 1.7966 or 1.797e0, not by 1.8 or 1.7976; `+1.4` by 1.4 or 1.37; a
quote's sign must be the output's). A "PHRASE" in double quotes (`"0 of 84 cells flagged"`, for
a count whose meaning is in its words) must occur verbatim in the text and in the output, runs of
spaces counted as one. Only the listed numbers and phrases are checked: the text's other
numbers (durations of runs, timings, years, equation and section numbers, inputs) are not
outputs. The text runs to the next blank line, fence, marker or heading; a list item's to its
next sibling item. A quote from a block that was skipped or failed is listed as not checked.

The run lists every block with what was done to it, the prose checks among them (kind `quotes`),
and counts both.

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
from decimal import Decimal
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SHELL_LANGS = {"sh", "bash", "shell"}
PYTHON_LANGS = {"python", "py", "python3"}
DEFAULT_TIMEOUT_S = 600
FEATURES = ("rerun",)
MARKER = re.compile(r"^\s*<!--\s*doc-test:\s*(.*?)\s*-->\s*$")
FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*([^\s`]*)")
LIST_ITEM = re.compile(r"^(\s*)([-*+]|\d+[.)])\s")
# A quoted number: an optional sign (`−` is the typographic minus), digits, a fraction, an
# exponent. Not preceded by a word character or a point, so "v2" or the "11" of "2026-11" is no
# signed number.
QUOTED = re.compile(r"(?<![\w.])([-+−]?)(\d+(?:\.\d*)?|\.\d+)(?:[eE]([-+]?\d+))?")


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
    name: str | None = None  # `name NAME`: what a `quotes from NAME` marker calls the block
    quotes: list[str] = field(default_factory=list)  # a prose check: the numbers it quotes
    source: str | None = None  # a prose check's `from NAME`; None: the command block before it
    status: str = ""
    seconds: float = 0.0

    @property
    def kind(self) -> str:
        if self.lang == "quotes":
            return "quotes"
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
    m = re.fullmatch(r"name\s+([A-Za-z0-9_.-]+)", body)
    if m:
        block.name = m.group(1)
        return
    if body.startswith("quotes"):
        raise MarkerError(f"{where}: `quotes` marks the paragraph below it, not a code fence")
    raise MarkerError(
        f"{where}: unknown marker {body!r}; expected skip (REASON), needs FEATURE, "
        f'replace "OLD" "NEW", env NAME=VALUE, timeout SECONDS, exit STATUS, output, name NAME '
        f"or (above a paragraph) quotes [from NAME] NUMBER..."
    )


def parse_quotes(body: str, where: str) -> tuple[str | None, list[str]]:
    """`quotes [from NAME] N1 N2 "PHRASE" ...` -> (NAME or None, the numbers as written and the
    phrases with their double quotes)."""
    m = re.fullmatch(r"quotes(?:\s+from\s+([A-Za-z0-9_.-]+))?(\s.*)?", body)
    if not m:
        raise MarkerError(f"{where}: expected quotes [from NAME] NUMBER..., got {body!r}")
    rest = m.group(2) or ""
    items = []
    for t in re.finditer(r'\s*(?:"([^"]+)"|(\S+))', rest):
        if t.group(1) is not None:
            items.append(f'"{t.group(1)}"')
        elif QUOTED.fullmatch(t.group(2)):
            items.append(t.group(2))
        else:
            raise MarkerError(f"{where}: `quotes`: {t.group(2)!r} is not a number (e.g. 1.797, -6.07, +1.4, "
                              f'2.2e-73) nor a "PHRASE" in double quotes')
    if not items:
        raise MarkerError(f"{where}: `quotes` lists no number: quotes [from NAME] NUMBER...")
    return m.group(1), items


def is_phrase(item: str) -> bool:
    return item.startswith('"')


def paragraph_end(lines: list[str], start: int) -> int:
    """The 0-based line after the paragraph, list item or table starting at `start`."""
    item = LIST_ITEM.match(lines[start])
    i = start + 1
    while i < len(lines):
        line = lines[i]
        if not line.strip() or FENCE.match(line) or MARKER.match(line) or line.lstrip().startswith("#"):
            break
        sibling = LIST_ITEM.match(line)
        if item and sibling and len(sibling.group(1)) <= len(item.group(1)):
            break
        i += 1
    return i


def extract(doc: Path) -> list[Block]:
    """The fenced blocks of one Markdown file with the markers directly above each."""
    rel = display(doc)
    lines = doc.read_text(encoding="utf-8").splitlines()
    blocks: list[Block] = []
    inside: set[int] = set()  # 0-based lines of fences and their bodies
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
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
        inside.update(range(start, i + 1))
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
    # Prose checks: a `quotes` marker directly above a paragraph, list item or table.
    names: dict[str, int] = {}
    for b in blocks:
        if b.name:
            if b.name in names:
                raise MarkerError(f"{rel}:{b.line}: block name {b.name!r} already names the block at line {names[b.name]}")
            names[b.name] = b.line
    for n, line in enumerate(lines):
        m = MARKER.match(line)
        if not m or n in used or n in inside or not m.group(1).startswith("quotes"):
            continue
        where = f"{rel}:{n + 1}"
        source, numbers = parse_quotes(m.group(1), where)
        if n + 1 >= len(lines) or not lines[n + 1].strip() or FENCE.match(lines[n + 1]) \
                or MARKER.match(lines[n + 1]):
            raise MarkerError(f"{where}: a `quotes` marker must sit directly above the paragraph it checks")
        if source is not None and (source not in names or names[source] > n):
            raise MarkerError(f"{where}: `quotes from {source}`: no command block above is named {source!r}"
                              + (f" (named: {', '.join(sorted(names))})" if names else ""))
        end = paragraph_end(lines, n + 1)
        text = "\n".join(lines[n + 1:end])
        flat = normalise(text.replace("−", "-"))
        absent = [q for q in numbers
                  if not shows(flat, normalise(q.strip('"') if is_phrase(q) else q.replace("−", "-")))]
        if absent:
            raise MarkerError(f"{where}: `quotes` lists {', '.join(absent)}, which the text below "
                              f"(lines {n + 2}–{end}) does not show")
        blocks.append(Block(rel, n + 2, "quotes", text, quotes=numbers, source=source))
        used.add(n)
    blocks.sort(key=lambda b: b.line)
    for n, line in enumerate(lines):
        if "doc-test:" in line and n not in used and n not in inside and MARKER.match(line):
            raise MarkerError(f"{rel}:{n + 1}: a doc-test marker must sit directly above a code fence"
                              " (or, for `quotes`, above a paragraph)")
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


def quoted_value(m: re.Match) -> tuple[Decimal, int]:
    """A QUOTED match as (value, exponent of its last printed digit): "1.797" -> (1.797, -3),
    "-6.07e1" -> (-60.7, -1), "25" -> (25, 0)."""
    sign, digits, exp = m.group(1), m.group(2), m.group(3)
    value = Decimal(("-" if sign in ("-", "−") else "") + digits + (f"e{exp}" if exp else ""))
    decimals = len(digits.split(".")[1]) if "." in digits else 0
    return value, int(exp or 0) - decimals


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
        # For prose checks: the command block just before, and each named block, with its
        # output when it ran (None when it was skipped, failed or not run).
        prev_cmd: Block | None = None
        outputs: dict[int, str | None] = {}
        named: dict[str, Block] = {}
        broken = None  # a failed block stops the document: later blocks depend on it
        last_failed = None  # with --keep-going: the command block before an output block failed
        for n, b in enumerate(blocks):
            if b.kind == "other":
                b.status = f"not a command ({b.lang or 'no language'})"
                continue
            if b.kind == "quotes":
                src = named.get(b.source) if b.source else prev_cmd
                if src is None:
                    self.fail(b, "a prose quote with no command block before it")
                elif outputs.get(src.line) is None:
                    why = ("ran with substitutions (other figures than the document's)"
                           if src.status.startswith("ran") else
                           "failed" if src.status == "FAILED" else src.status.split(":")[0])
                    b.status = f"not checked: its block at line {src.line} {why}"
                else:
                    self.check_quotes(b, src, outputs[src.line])
                continue
            if b.kind == "output":
                if broken or last_failed:
                    b.status = f"not checked: block at line {broken or last_failed} failed"
                elif last_output is None:
                    self.fail(b, "an output block with no command block before it")
                else:
                    self.check_output(b, *last_output)
                continue
            prev_cmd = b
            outputs[b.line] = None
            if b.name:
                named[b.name] = b
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
                    # A block run with substitutions prints other figures than the document's.
                    outputs[b.line] = None if b.replace else output
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

    def check_quotes(self, b: Block, cmd_block: Block, output: str) -> None:
        """Each number a prose paragraph quotes must be shown by the command's output to the
        digits the paragraph prints it with."""
        found = [(m.group(0), quoted_value(m)) for m in QUOTED.finditer(output.replace("−", "-"))]
        missing = []
        for q in b.quotes:
            if is_phrase(q):
                if not shows(normalise(output), normalise(q.strip('"'))):
                    missing.append(q)
                continue
            value, exp = quoted_value(QUOTED.fullmatch(q.replace("−", "-")))
            half = Decimal(5).scaleb(exp - 1)  # half a unit of the quote's last digit
            if not any(e <= exp and abs(v - value) <= half for _, (v, e) in found):
                # The nearest in size, then in value: a sign flip shows as such.
                near = min(found, key=lambda f: (abs(abs(f[1][0]) - abs(value)), abs(f[1][0] - value)),
                           default=None)
                missing.append(f"{q}" + (f" (nearest in the output: {near[0]})" if near else ""))
        src = f"line {cmd_block.line}" + (f" ({b.source})" if b.source else "")
        if missing:
            self.fail(b, f"the output of the block at {src} no longer shows, to the printed digits:\n"
                         + "\n".join(f"    {m}" for m in missing)
                         + f"\n  the text:\n{tail(b.text, 8)}")
        else:
            b.status = f"checked: {len(b.quotes)} figure(s) against {src}"

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

<!-- doc-test: name rate -->
```sh
echo "rate on x: 1.797 [1.714, 1.880] deg/h, -6.0661, took 0.9 s"
```

<!-- doc-test: quotes 1.797 1.714 1.880 -6.07 "rate on x" -->
The rate on x is 1.797 [1.714, 1.880] and on z −6.07, in 2.2 s (1 run, Eq. 11).

<!-- doc-test: quotes 1.797 1.71 1.881 -6.066 -->
- the rate 1.797 [1.71, 1.881], −6.066: 1.881 is not 1.880 to its digits
- a sibling item, not part of the paragraph above: 9.99

```sh
echo "coarse: 1.8; sign: 2.5"
```

<!-- doc-test: quotes 1.797 -2.5 "sign: -2.5" -->
1. Finer digits than printed (1.797) and the other sign (-2.5) are not shown, nor "sign: -2.5".

<!-- doc-test: quotes from rate 0.9 -->
| figure | value |
|---|---|
| from the named block | 0.9 |

<!-- doc-test: skip (a reason) -->
```sh
echo 42
```

<!-- doc-test: quotes 42 -->
A quote of a skipped block: 42.
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
    (60, "ran", ""),
    (65, "checked: 5 figure(s)", ""),  # rounding -6.0661 to -6.07; other numbers not listed
    (68, "FAILED", "1.881 (nearest in the output: 1.880)"),  # a list item alone
    (71, "ran", ""),
    (76, "FAILED", "1.797 (nearest in the output: 1.8)"),  # and -2.5 (a named block follows)
    (79, "checked: 1 figure(s) against line 60 (rate)", ""),
    (84, "skipped: a reason", ""),
    (89, "not checked: its block at line 84 skipped", ""),
]

# Malformed prose markers: the document is refused (exit status 2), naming the line.
SELF_TEST_BAD = [  # (document, text the error must hold)
    ("<!-- doc-test: quotes 1.5 -->\nThe figure is 1.50.\n", "does not show"),
    ("<!-- doc-test: quotes 1.5 -->\n\nThe figure is 1.5.\n", "directly above the paragraph"),
    ("<!-- doc-test: quotes from nope 1.5 -->\nThe figure is 1.5.\n", "no command block above is named"),
    ("<!-- doc-test: quotes -->\nThe figure is 1.5.\n", "lists no number"),
    ("<!-- doc-test: quotes 1.5 abc -->\nThe figure is 1.5 abc.\n", "is not a number"),
    ('<!-- doc-test: quotes "5 cells" -->\nThe 15 cells\n', "does not show"),
    ("<!-- doc-test: quotes 9.99 -->\n- an item: 1.5\n- its sibling: 9.99\n", "does not show"),
    ("<!-- doc-test: quotes 1.5 -->\n```sh\necho 1.5\n```\n", "not a code fence"),
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
    # The failing quote of the block at line 76 names both numbers it misses.
    if not any("block at line 76 " in f and "-2.5 (nearest in the output: 2.5)" in f
               and '"sign: -2.5"' in f for f in runner.failures):
        bad.append("block at line 76: the quote of the other sign (-2.5) or the phrase is not named")
    for text, want in SELF_TEST_BAD:
        with tempfile.TemporaryDirectory() as d:
            doc = Path(d) / "bad.md"
            doc.write_text(text)
            try:
                extract(doc)
                bad.append(f"malformed quote accepted: {text.splitlines()[0]!r}")
            except MarkerError as e:
                if want not in str(e):
                    bad.append(f"malformed quote {text.splitlines()[0]!r}: error {e} lacks {want!r}")
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
    total = len(SELF_TEST_EXPECT) + 2 + len(SELF_TEST_BAD)
    print(f"doc-test self-test: {total - len(bad)} of {total} checks passed")
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
                        [f'replace "{o}" "{n}"' for o, n in b.replace] + [f"env {k}" for k in b.env] + \
                        ([f"name {b.name}"] if b.name else []) + \
                        ([f"quotes{' from ' + b.source if b.source else ''} {' '.join(b.quotes)}"] if b.quotes else [])
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
    prose: dict[str, int] = {}
    for _, blocks in per_doc:
        for b in blocks:
            key = next((k for k in ("not a command", "not run", "not checked") if b.status.startswith(k)),
                       b.status.split(" ")[0].rstrip(":"))
            tally = prose if b.kind == "quotes" else counts
            tally[key] = tally.get(key, 0) + 1
    numbers = sum(len(b.quotes) for _, blocks in per_doc for b in blocks
                  if b.kind == "quotes" and b.status.startswith("checked"))
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
    prose_summary = ", ".join(f"{v} {k}" for k, v in sorted(prose.items())) or "none"
    print(f"doc-test: blocks: {summary}; prose checks (quotes): {prose_summary}"
          f" ({numbers} quoted figure(s) checked) in {time.monotonic() - t0:.0f} s")
    if runner.failures:
        print(f"doc-test: {len(runner.failures)} failure(s):", file=sys.stderr)
        for f in runner.failures:
            print(f"  {f.splitlines()[0]}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
