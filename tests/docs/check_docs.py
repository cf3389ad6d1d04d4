#!/usr/bin/env python3
"""Keeps README.md and docs/ true to the product.

Every relative link must resolve. Every command in a ```sh block must be one a reader can
type: a `build/sim/vmt` command names a subcommand and options its --help lists and files that
exist; a `bash tools/...` or `python3 ...` command names a script that exists. The quick vmt
commands (check, signals, snapshot, imgdiff, run of a scene) are run against the build in a
scratch folder and must succeed. A block preceded by `<!-- illustrative -->` shows a command
whose files the reader brings (or which runs for long): only its subcommand and options are
checked.

Usage: check_docs.py SOURCE_DIR VMT_BINARY
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

LINK = re.compile(r"(?<!\!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^```(\w*)\s*$")
RUN_QUICK = {"check", "signals", "snapshot", "imgdiff", "run"}
# Options every vmt subcommand takes without listing them.
COMMON_OPTIONS = {"--help", "-h"}


def markdown_files(src):
    yield os.path.join(src, "README.md")
    for root, _, files in os.walk(os.path.join(src, "docs")):
        for f in sorted(files):
            if f.endswith(".md"):
                yield os.path.join(root, f)
    for extra in ("bench/README.md", "CHANGELOG.md"):
        path = os.path.join(src, extra)
        if os.path.exists(path):
            yield path


def shell_blocks(text):
    """(first line number, lines, illustrative) of each sh/bash/console block."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        lang, start = m.group(1), i
        i += 1
        body = []
        while i < len(lines) and not lines[i].startswith("```"):
            body.append(lines[i])
            i += 1
        i += 1
        if lang not in ("sh", "bash", "console", "shell"):
            continue
        before = start - 1
        while before >= 0 and not lines[before].strip():
            before -= 1
        illustrative = before >= 0 and "<!-- illustrative -->" in lines[before]
        yield start + 2, body, illustrative


def commands(body):
    """Joined command lines (continuations folded), without comments and prompts."""
    pending = ""
    for offset, raw in enumerate(body):
        line = raw.rstrip()
        if line.startswith("$ "):
            line = line[2:]
        if pending:
            line = pending + " " + line.strip()
        if line.endswith("\\"):
            pending = line[:-1].rstrip()
            continue
        pending = ""
        code = line.split(" #", 1)[0].strip() if not line.lstrip().startswith("#") else ""
        if code:
            yield offset, code


def without_redirections(words):
    """The command's own words: no `> file`, `2>&1`, `< file` or a trailing `&`."""
    out, skip = [], False
    for w in words:
        if skip:
            skip = False
        elif re.fullmatch(r"\d*[<>]{1,2}", w):
            skip = True
        elif re.fullmatch(r"\d*[<>]{1,2}&?\S+", w) or w == "&":
            pass
        else:
            out.append(w)
    return out


class Checker:
    def __init__(self, src, vmt):
        self.src = src
        self.vmt = vmt
        self.errors = []
        self.help = {}
        self.scratch = tempfile.mkdtemp(prefix="vmt-docs-")
        for name in ("scenes", "models", "tests", "examples", "docs", "tools", "bench"):
            os.symlink(os.path.join(src, name), os.path.join(self.scratch, name))
        os.makedirs(os.path.join(self.scratch, "build", "sim"))
        os.symlink(vmt, os.path.join(self.scratch, "build", "sim", "vmt"))

    def fail(self, where, text):
        self.errors.append(f"{where}: {text}")

    def help_of(self, words):
        key = tuple(words)
        if key not in self.help:
            try:
                out = subprocess.run([self.vmt, *words, "--help"], capture_output=True, text=True,
                                     timeout=60)
                self.help[key] = out.stdout if out.returncode == 0 else None
            except (OSError, subprocess.TimeoutExpired) as e:
                sys.exit(f"docs: cannot run {self.vmt}: {e}")
        return self.help[key]

    def check_links(self, path, text):
        base = os.path.dirname(path)
        for n, line in enumerate(text.split("\n"), 1):
            for m in LINK.finditer(line):
                target = m.group(1) or m.group(2)
                if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                    continue
                file = target.split("#", 1)[0]
                if not os.path.exists(os.path.normpath(os.path.join(base, file))):
                    self.fail(f"{path}:{n}", f"link '{target}' does not resolve")

    def check_vmt(self, where, words, run):
        args = words[1:]
        path = []
        while args and not args[0].startswith("-") and self.help_of(path + [args[0]]) \
                and args[0] in (self.help_of(path) or ""):
            path.append(args.pop(0))
            if "Subcommands:" not in (self.help_of(path) or ""):
                break
        if not path:
            self.fail(where, f"'{' '.join(words)}': no such vmt subcommand")
            return
        help_text = self.help_of(path) or ""
        for a in args:
            if a.startswith("-"):
                option = a.split("=", 1)[0]
                if option not in COMMON_OPTIONS and not re.search(
                        r"(^|[\s,])" + re.escape(option) + r"\b", help_text):
                    self.fail(where, f"vmt {' '.join(path)} has no option '{option}'")
            elif run and re.search(r"\.(ya?ml|mtc|isg|png)$", a) and not a.startswith(("out/", "/tmp")):
                if not os.path.exists(os.path.join(self.scratch, a)):
                    self.fail(where, f"file '{a}' does not exist")
        if run and path[0] in RUN_QUICK and "--http" not in args:
            try:
                out = subprocess.run(words, cwd=self.scratch, capture_output=True, text=True,
                                     timeout=300, env=dict(os.environ, GALLIUM_DRIVER="llvmpipe"))
            except (OSError, subprocess.TimeoutExpired) as e:
                self.fail(where, f"'{' '.join(words)}' did not run: {e}")
                return
            if out.returncode != 0:
                tail = (out.stderr or out.stdout).strip().split("\n")[-1:]
                self.fail(where, f"'{' '.join(words)}' exited {out.returncode}: {tail}")

    def check_command(self, where, code, run):
        for part in re.split(r"\s*(?:&&|;|\|\|?)\s*", code):
            try:
                words = shlex.split(part)
            except ValueError as e:
                self.fail(where, f"cannot parse '{part}': {e}")
                continue
            while words and "=" in words[0] and not words[0].startswith("-"):
                words = words[1:]  # VAR=value prefixes
            words = without_redirections(words)
            if not words:
                continue
            if words[0] == "build/sim/vmt":
                self.check_vmt(where, words, run)
            elif words[0] in ("bash", "python3", "sh") and len(words) > 1:
                if not os.path.exists(os.path.join(self.src, words[1])):
                    self.fail(where, f"script '{words[1]}' does not exist")
            elif words[0].startswith("build/"):
                self.fail(where, f"'{words[0]}' is not something the build makes (vmt is build/sim/vmt)")
            elif words[0].startswith(("tools/", "bench/", "examples/", "./tools/")):
                if not os.path.exists(os.path.join(self.src, words[0])):
                    self.fail(where, f"script '{words[0]}' does not exist")

    def check_file(self, path):
        text = open(path, encoding="utf-8").read()
        self.check_links(path, text)
        for first, body, illustrative in shell_blocks(text):
            for offset, code in commands(body):
                self.check_command(f"{path}:{first + offset}", code, not illustrative)


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().split("\n")[-1], file=sys.stderr)
        return 2
    src, vmt = (os.path.abspath(a) for a in sys.argv[1:])
    checker = Checker(src, vmt)
    files = list(markdown_files(src))
    try:
        for path in files:
            checker.check_file(path)
    finally:
        shutil.rmtree(checker.scratch, ignore_errors=True)
    for e in checker.errors:
        print(e)
    print(f"docs: {len(files)} files, {len(checker.errors)} problems")
    return 1 if checker.errors else 0


if __name__ == "__main__":
    sys.exit(main())
