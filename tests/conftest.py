"""Fixtures shared by test modules: ``suggest`` on the invalid catalog designs, computed
once per session and only for the (design, model) pairs a test asks for."""

from __future__ import annotations

from pathlib import Path

import pytest

from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.suggest import suggest_design

CATALOG = Path(__file__).resolve().parents[1] / "designs"


@pytest.fixture(scope="session")
def catalog_suggestions():
    """``get(name, model)`` -> (the catalog design in that model, its ``SuggestionReport``),
    each computed on first use (the line searches are the slow part)."""
    cache: dict[tuple[str, str], tuple] = {}

    def get(name: str, model: str):
        if (name, model) not in cache:
            design = with_model(load_design(str(CATALOG / name)), model)
            cache[(name, model)] = (design, suggest_design(design))
        return cache[(name, model)]

    return get
