import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def examples():
    return ROOT / "examples"


@pytest.fixture
def romdyn_cli():
    """The CLI built by `cargo test`/`cargo build` (ROMDYN_BIN overrides)."""
    path = pathlib.Path(os.environ.get("ROMDYN_BIN", ROOT / "target" / "debug" / "romdyn"))
    assert path.exists(), f"the romdyn CLI is not built at {path}: run cargo build (or set ROMDYN_BIN)"
    return path
