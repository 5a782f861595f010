"""The examples and the package run on the package's oldest Python (``requires-python``): they
parse as Python 3.10 and import ``tomllib`` (3.11+) only with the ``tomli`` fallback."""

import ast
from pathlib import Path

import pytest

PYTHON = Path(__file__).resolve().parents[1]
SOURCES = sorted((PYTHON / "examples").glob("*.py")) + sorted((PYTHON / "fairgrasp").glob("*.py"))


def test_the_package_declares_python_3_10():
    assert 'requires-python = ">=3.10"' in (PYTHON / "pyproject.toml").read_text()


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: p.name)
def test_every_source_parses_as_python_3_10_and_guards_tomllib(path):
    tree = ast.parse(path.read_text(), filename=str(path), feature_version=(3, 10))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import) and any(a.name == "tomllib" for a in node.names):
            guarded = [
                t for t in ast.walk(tree)
                if isinstance(t, ast.Try) and node in t.body
                and any(isinstance(i, ast.Import) and i.names[0].name == "tomli"
                        for h in t.handlers for i in h.body)
            ]
            assert guarded, f"{path.name}:{node.lineno}: `import tomllib` needs Python 3.11; add the tomli fallback"
