"""Shared helpers: the CLI binary and the Rust reference run, both given by tests/python_package.rs
through environment variables (skipped when the tests are run by hand without them)."""

import json
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("FAIRGRASP_BIN")
    if not path:
        pytest.skip("FAIRGRASP_BIN not set (run through cargo test --test python_package)")

    def run(*args):
        out = subprocess.run([path, *args], capture_output=True, text=True, check=True)
        return json.loads(out.stdout)

    return run


@pytest.fixture(scope="session")
def rust_reference():
    path = os.environ.get("FAIRGRASP_RUST_REFERENCE")
    if not path:
        pytest.skip("FAIRGRASP_RUST_REFERENCE not set (run through cargo test --test python_package)")
    with open(path) as f:
        return json.load(f)
