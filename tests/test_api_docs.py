"""Every public function and class on the site's API page has a numpydoc docstring that documents
each of its parameters (names as in the signature, each with a description: its unit, where it
has one)."""

import importlib
import inspect
import re

import pytest
from numpydoc.docscrape import FunctionDoc

import fetorsion

from conftest import ROOT


def api_names() -> list[str]:
    """The names the API page lists in its autosummary tables (module ``fetorsion``)."""
    text = (ROOT / "docs/api.md").read_text()
    names = []
    for block in re.findall(r"\.\. autosummary::\n((?:   .*\n|\n)+)", text):
        names += [line.strip() for line in block.splitlines() if line.strip() and not line.strip().startswith(":")]
    return names


def documented_parameters(func) -> dict[str, str]:
    doc = FunctionDoc(func)
    out = {}
    for p in doc["Parameters"]:
        for name in p.name.split(","):  # "method, samples, seed": documented together
            out[name.strip().lstrip("*")] = " ".join(p.desc).strip()
    return out


def signature_parameters(func) -> list[str]:
    return [n for n in inspect.signature(func).parameters if n not in ("self", "cls")]


def test_the_api_page_lists_the_public_api():
    names = api_names()
    assert set(fetorsion.__all__) - {"PARTITIONS"} <= set(names), set(fetorsion.__all__) - set(names)


def resolve(name: str):
    """A name of the API page: ``fetorsion``'s own, or a dotted path to a module's function."""
    if "." not in name:
        return getattr(fetorsion, name)
    module, _, attr = name.rpartition(".")  # relative to the page's current module, fetorsion
    return getattr(importlib.import_module(f"fetorsion.{module}"), attr)


@pytest.mark.parametrize("name", api_names())
def test_documented(name):
    obj = resolve(name)
    assert inspect.getdoc(obj), f"{name} has no docstring"
    if inspect.isclass(obj):
        for attr, member in vars(obj).items():
            if not attr.startswith("_") and inspect.isfunction(member):
                assert inspect.getdoc(member), f"{name}.{attr} has no docstring"
        return
    documented = documented_parameters(obj)
    for p in signature_parameters(obj):
        assert p in documented, f"{name}: parameter {p!r} is not in its Parameters section"
        assert documented[p], f"{name}: parameter {p!r} has no description"
