"""The shared vectors on disk are what the generator (nav2_pyif_codegen.vectors, the
``nav2-pyif-vectors`` command) writes: each .msgpack, its .json form and the index."""

from __future__ import annotations

import pytest
from nav2_pyif_codegen.vectors import build_vectors, rendered_files

from tests.test_vectors import VECTORS

pytestmark = pytest.mark.unit


def test_vector_files_are_what_the_code_generates() -> None:
    files = rendered_files(build_vectors())
    on_disk = {str(p.relative_to(VECTORS)) for p in VECTORS.rglob("*") if p.is_file()}
    assert on_disk == set(files), "run: nav2-pyif-vectors --write protocol/vectors"
    for name, content in files.items():
        assert (VECTORS / name).read_bytes() == content, name
