"""Every snippet of docs/python.md runs: each ```python block on its own, in a scratch
directory (with the repository's scenes/ beside it), and the import line its ```sh block and the
README's Python section show, with the module this suite tests."""
import os
import re
import shlex
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

DOC = SOURCE_DIR / "docs" / "python.md"


def blocks(lang, page=DOC):
    text = page.read_text()
    return [m.group(1) for m in re.finditer(r"^```" + lang + r"\n(.*?)^```", text, re.S | re.M)]


PYTHON_BLOCKS = blocks("python")


def test_the_page_has_snippets():
    assert len(PYTHON_BLOCKS) >= 6 and blocks("sh")


@pytest.mark.parametrize("index", range(len(PYTHON_BLOCKS)))
def test_python_snippet_runs(index, tmp_path, monkeypatch, vulkan):
    (tmp_path / "scenes").symlink_to(SOURCE_DIR / "scenes")
    monkeypatch.chdir(tmp_path)
    code = compile(PYTHON_BLOCKS[index], f"{DOC}:python block {index + 1}", "exec")
    exec(code, {"__name__": "__doc_snippet__"})


@pytest.mark.parametrize("page", [DOC, SOURCE_DIR / "README.md"], ids=["python.md", "README"])
def test_shown_import_line_lists_cpu_and_vulkan(page, vulkan):
    (line,) = [l for b in blocks("sh", page) for l in b.splitlines() if "import masav" in l]
    words = shlex.split(line)
    assert words[0] == "PYTHONPATH=build/ci/python" and words[1] == "python3"
    # The module this suite tests, where the page says build/ci/python; Debian's interpreter.
    env = dict(os.environ, PYTHONPATH=os.environ["MASAV_PYTHON_DIR"])
    out = subprocess.run([sys.executable] + words[2:], env=env, cwd=SOURCE_DIR,
                         capture_output=True, text=True, check=True).stdout
    assert "<cpu: available" in out and "<vulkan: available" in out
