#!/usr/bin/env bash
# docs_commands.sh SOURCE_DIR BUILD_DIR
# Every command the README and docs/*.md show is run by a test. Reads each ```sh (or bash,
# shell) block of SOURCE_DIR/README.md and SOURCE_DIR/docs/*.md and takes every command that
# runs `masav`, `build/<dir>/masav` or `tools/<name>` (after VAR=value assignments or an
# `mpirun -np N` prefix). A shown command is matched by a test registered in BUILD_DIR
# (`ctest --show-only=json-v1`) whose command line runs the same thing: the same subcommand
# words, every positional (by file name), every option the shown line gives with its value
# (path-valued options such as --out may name another path), each shown VAR=value in the test's
# command or environment, and the shown `-np N`. A test may add options (smaller sizes, -q,
# --json). The few commands that cannot run under ctest are in EXEMPT below, each with the test
# that runs it another way. Syntax summaries belong in ```text blocks, which are not read.
# Prints each shown command with the test that runs it, or UNMATCHED; exits 1 if any is
# unmatched.
set -u
[[ $# -eq 2 ]] || { echo "usage: docs_commands.sh SOURCE_DIR BUILD_DIR"; exit 2; }
src=$1 build=$2
list=$(mktemp)
trap 'rm -f "$list"' EXIT
if ! ctest --test-dir "$build" --show-only=json-v1 >"$list" 2>&1; then
  printf 'docs_commands: ctest --show-only=json-v1 failed in %s:\n' "$build"
  cat "$list"
  exit 1
fi
python3 - "$src" "$list" <<'PY'
import glob
import json
import os
import re
import shlex
import sys

src, listing = sys.argv[1], sys.argv[2]

# Commands no ctest can run as shown, and the registered test that runs them another way (None:
# the command is the entry point that builds what ctest runs).
EXEMPT = {
    "tools/run": (None, "the quick start: it builds masav; cli.readme_build_dirs checks the binary it builds"),
    "tools/test": (None, "the quick start: it builds the tests and runs ctest itself"),
    "tools/gpu-report": ("tools.gpu_report.quick", "a machine's record; its --quick form runs through tests/gpu_report.cmake"),
    "tools/gpu-pack": ("tools.gpu_pack", "runs through tests/gpu_pack.sh"),
    "tools/gpu-unpack": ("tools.gpu_unpack", "runs through tests/gpu_unpack.sh"),
}
# Options whose value is a path the test may choose itself.
PATH_OPTIONS = {"--out", "--csv", "--json", "--checkpoint-dir", "--restart", "--tf", "--script",
                "--data", "--masav", "--mpirun", "--build-dir"}
ALIASES = {"-o": "--out", "-q": "--quiet", "-b": "--backend", "-d": "--device", "-p": "--preset",
           "-r": "--reference"}
NUMBER = re.compile(r"^-?[0-9.]+([eE][-+]?[0-9]+)?$")
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")
SEPARATORS = {"&&", "||", ";", "|", "&"}
LAUNCHERS = {"mpirun", "mpiexec"}


def split_segments(text):
    """Shell words of a command line, cut at && || ; | (comments dropped)."""
    lex = shlex.shlex(text, posix=True, punctuation_chars=";&|")
    lex.whitespace_split = True
    lex.commenters = "#"
    segments, cur = [], []
    for tok in lex:
        if tok in SEPARATORS:
            segments.append(cur)
            cur = []
        else:
            cur.append(tok)
    segments.append(cur)
    return [s for s in segments if s]


def is_option(tok):
    return tok.startswith("-") and len(tok) > 1 and not NUMBER.match(tok)


def parse_args(args):
    """(positionals, [(option, value or None)]) of a command's arguments."""
    positionals, options, i = [], [], 0
    while i < len(args):
        tok = args[i]
        if tok == "--":
            positionals += args[i + 1:]
            break
        if is_option(tok):
            name, value = tok, None
            if tok.startswith("--") and "=" in tok:
                name, value = tok.split("=", 1)
            elif i + 1 < len(args) and not is_option(args[i + 1]):
                value = args[i + 1]
                i += 1
            options.append((ALIASES.get(name, name), value))
        else:
            positionals.append(tok)
        i += 1
    return positionals, options


def program(tok):
    """'masav' for a masav binary, 'tools/NAME' for a tool, else None."""
    if tok == "masav" or tok.endswith("/masav"):
        return "masav"
    m = re.search(r"(?:^|/)tools/([A-Za-z0-9_.-]+)$", tok)
    return f"tools/{m.group(1)}" if m else None


class Invocation:
    def __init__(self, prog, args, env, np):
        self.prog, self.env, self.np = prog, env, np
        words = []
        if prog == "masav":
            rest = list(args)
            if rest and not is_option(rest[0]):
                words.append(rest.pop(0))
                if words[0] == "bench" and rest and not is_option(rest[0]):
                    words.append(rest.pop(0))
            args = rest
        self.words = words
        self.positionals, self.options = parse_args(args)


def invocation_of_segment(seg):
    """The shown command of one shell segment, or None when it runs neither masav nor a tool."""
    env, np, i = {}, None, 0
    while i < len(seg) and (ASSIGNMENT.match(seg[i]) or seg[i] == "env"):
        if seg[i] != "env":
            k, v = seg[i].split("=", 1)
            env[k] = v
        i += 1
    if i < len(seg) and os.path.basename(seg[i]) in LAUNCHERS:
        i += 1
        while i < len(seg) and program(seg[i]) is None:
            if seg[i] in ("-np", "-n") and i + 1 < len(seg):
                np = seg[i + 1]
                i += 1
            i += 1
    if i >= len(seg) or program(seg[i]) is None:
        return None
    return Invocation(program(seg[i]), seg[i + 1:], env, np)


def shown_commands():
    files = [os.path.join(src, "README.md")] + sorted(glob.glob(os.path.join(src, "docs", "*.md")))
    out = []
    for path in files:
        rel = os.path.relpath(path, src)
        fence, lines = None, []
        for n, line in enumerate(open(path, encoding="utf-8"), 1):
            s = line.strip()
            if fence is None:
                m = re.match(r"^(`{3,})\s*([A-Za-z]*)", s)
                if m:
                    fence = (m.group(1), m.group(2).lower())
                continue
            if s.startswith(fence[0]) and s.strip("`") == "":
                fence = None
                continue
            if fence[1] in ("sh", "bash", "shell"):
                lines.append((n, line.rstrip("\n")))
            continue
        # Join continuation lines.
        joined, start, buf = [], None, ""
        for n, text in lines:
            if start is None:
                start = n
            if text.endswith("\\"):
                buf += text[:-1] + " "
                continue
            joined.append((start, buf + text))
            start, buf = None, ""
        for n, text in joined:
            try:
                segments = split_segments(text)
            except ValueError as e:
                out.append((rel, n, text.strip(), None, f"cannot parse: {e}"))
                continue
            for seg in segments:
                inv = invocation_of_segment(seg)
                if inv:
                    out.append((rel, n, " ".join(seg), inv, None))
    return out


def test_invocations(test):
    """Every masav or tool invocation in a registered test's command line, with its environment."""
    env = {}
    for prop in test.get("properties", []):
        if prop["name"] == "ENVIRONMENT":
            for kv in prop["value"]:
                if "=" in kv:
                    k, v = kv.split("=", 1)
                    env[k] = v
    cmd = list(test.get("command") or [])
    # `sh -c SCRIPT ARG0 ARG1 ...`: the script's words, $0.. replaced by the arguments.
    segments, i = [], 0
    plain = []
    while i < len(cmd):
        if cmd[i] == "-c" and i > 0 and os.path.basename(cmd[i - 1]) in ("sh", "bash") and i + 1 < len(cmd):
            script, params = cmd[i + 1], cmd[i + 2:]
            for k in range(len(params) - 1, -1, -1):
                script = script.replace(f"${k}", shlex.quote(params[k]))
            segments += split_segments(script)
            break
        plain.append(cmd[i])
        i += 1
    segments.insert(0, plain)
    found = []
    for seg in segments:
        local_env, np, launcher = dict(env), None, False
        for j, tok in enumerate(seg):
            if ASSIGNMENT.match(tok) and not tok.startswith("-"):
                k, v = tok.split("=", 1)
                local_env[k] = v
            if os.path.basename(tok) in LAUNCHERS:
                launcher = True
            if launcher and tok in ("-np", "-n") and j + 1 < len(seg):
                np = seg[j + 1]
            base = os.path.basename(tok)
            if base == "demo_xvfb.sh" and j + 3 < len(seg):
                # demo_xvfb.sh MASAV SCRIPT SHOTS ARGS... runs `MASAV demo ARGS... --script SCRIPT`.
                found.append(Invocation("masav", ["demo"] + seg[j + 4:] + ["--script", seg[j + 2]],
                                        local_env, np))
            prog = program(tok)
            if prog:
                found.append(Invocation(prog, seg[j + 1:], local_env, np))
    return found


def matches(shown, inv):
    if shown.prog != inv.prog or shown.words != inv.words[:len(shown.words)] or \
            len(shown.words) != len(inv.words):
        return False
    have = set(inv.options)
    names = {o for o, _ in inv.options}
    for opt, val in shown.options:
        if opt in PATH_OPTIONS:
            if opt not in names:
                return False
        elif (opt, val) not in have:
            return False
    bases = {os.path.basename(p.rstrip("/")) for p in inv.positionals}
    for p in shown.positionals:
        if os.path.basename(p.rstrip("/")) not in bases:
            return False
    for k, v in shown.env.items():
        if inv.env.get(k) != v:
            return False
    if shown.np is not None and inv.np != shown.np:
        return False
    return True


tests = json.load(open(listing))["tests"]
names = {t["name"] for t in tests}
invocations = [(t["name"], inv) for t in tests for inv in test_invocations(t)]
has_mpi = any(os.path.basename(tok) in LAUNCHERS for t in tests for tok in (t.get("command") or []))

shown = shown_commands()
unmatched = 0
for rel, n, text, inv, error in shown:
    where = f"{rel}:{n}"
    if error:
        print(f"UNMATCHED  {where}  {text}  ({error})")
        unmatched += 1
        continue
    if inv.prog in EXEMPT:
        test, why = EXEMPT[inv.prog]
        if test is not None and test not in names:
            print(f"UNMATCHED  {where}  {text}  (exempt only through {test}, which is not registered)")
            unmatched += 1
        else:
            print(f"exempt     {where}  {text}  ({why})")
        continue
    if not has_mpi and (inv.np is not None or inv.prog == "tools/sph-ranks-bench"):
        print(f"skipped    {where}  {text}  (this build has no MPI tests)")
        continue
    hits = [name for name, t in invocations if matches(inv, t)]
    if hits:
        more = f" (+{len(hits) - 1} more)" if len(hits) > 1 else ""
        print(f"ok         {where}  {text}  <- {hits[0]}{more}")
    else:
        print(f"UNMATCHED  {where}  {text}")
        unmatched += 1

print(f"{len(shown)} shown commands, {unmatched} not run by any test")
if not shown:
    print("no shown commands found: is SOURCE_DIR the repository root?")
    sys.exit(1)
if unmatched:
    print("add a test that runs each UNMATCHED command (tests/CMakeLists.txt, masav_cli_test), "
          "or show its syntax in a ```text block")
    sys.exit(1)
PY
