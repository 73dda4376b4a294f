"""The documentation read as a reference (issue 41): every analysis page has its assumptions,
typeset equations, sources and validation under their own headings; no page has an empty heading
or a paragraph cut off mid-sentence."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[1] / "docs"
#: The analysis pages: each carries the four headings (issue 41).
ANALYSIS_PAGES = ("lumped", "fe-modal", "campbell", "forced-response", "dampers", "calibration", "measured-data",
                  "condensed-crank", "networks-and-transients", "fillet-stress", "fatigue",
                  "studies", "design-search")
HEADINGS = ("Assumptions", "Equations", "Sources", "Validation")


def blocks(text: str):
    """(kind, text) of each block of a Markdown page: code fences, math, headings, tables, lists
    and paragraphs, in order."""
    lines, out, k = text.splitlines(), [], 0
    while k < len(lines):
        line = lines[k]
        if line.startswith("```") or line.startswith(":::"):
            fence, j = line[:3], k + 1
            while j < len(lines) and not lines[j].startswith(fence):
                j += 1
            out.append(("code", "\n".join(lines[k:j + 1])))
            k = j + 1
        elif line.startswith("$$"):
            j = k
            while not (lines[j].rstrip().endswith("$$") and (j > k or len(lines[j].strip()) > 2)):
                j += 1
            out.append(("math", "\n".join(lines[k:j + 1])))
            k = j + 1
        elif line.startswith("#"):
            out.append(("heading", line))
            k += 1
        elif line.strip() in ("---", "***", "___"):
            out.append(("rule", line))
            k += 1
        elif line.startswith(("  ", "\t")) and not re.match(r"\s*([-*+]|\d+\.) ", line):
            # an indented display (a formula set off by indentation, a list item's continuation)
            j = k
            while j < len(lines) and (lines[j].startswith(("  ", "\t")) or not lines[j].strip()):
                j += 1
            out.append(("code", "\n".join(lines[k:j])))
            k = j
        elif not line.strip():
            k += 1
        else:
            j = k
            while j < len(lines) and lines[j].strip() and not lines[j].startswith(("#", "```", "$$", ":::")):
                j += 1
            body = "\n".join(lines[k:j])
            kind = "table" if line.startswith("|") else "list" if re.match(r"\s*([-*+]|\d+\.) ", line) else "paragraph"
            out.append((kind, body))
            k = j
    return out


@pytest.mark.parametrize("page", ANALYSIS_PAGES)
def test_an_analysis_page_has_assumptions_equations_sources_and_validation(page):
    text = (DOCS / f"{page}.md").read_text()
    heads = [line.lstrip("#").strip() for kind, line in blocks(text) if kind == "heading" and line.startswith("## ")]
    for h in HEADINGS:
        assert h in heads, f"{page}.md has no '## {h}'"
    assert [h for h in heads if h in HEADINGS] == list(HEADINGS), f"{page}.md: the four headings out of order"
    section = text.split("## Equations", 1)[1].split("\n## ", 1)[0]
    assert re.search(r"\$\$.+?\$\$", section, re.S), f"{page}.md: no typeset equation under Equations"
    assert "references.md" in text.split("## Sources", 1)[1].split("\n## ", 1)[0], \
        f"{page}.md: its Sources do not link the bibliography"


@pytest.mark.parametrize("page", sorted(p.stem for p in DOCS.glob("*.md")))
def test_no_empty_heading_and_no_paragraph_cut_off(page):
    """A heading followed by another of the same or a higher level (or the end) is empty; a
    paragraph that does not lead into a display (code, equation, table, list) and whose last
    character cannot end a sentence was cut off (the defect of the old forced-response page,
    which stopped at "...speed: the")."""
    bl = blocks((DOCS / f"{page}.md").read_text())
    for k, (kind, text) in enumerate(bl):
        if kind == "heading":
            level = len(text) - len(text.lstrip("#"))
            nxt = bl[k + 1] if k + 1 < len(bl) else None
            empty = nxt is None or (nxt[0] == "heading" and len(nxt[1]) - len(nxt[1].lstrip("#")) <= level)
            assert not empty, f"{page}.md: the heading {text!r} has nothing under it"
        leads_in = k + 1 < len(bl) and bl[k + 1][0] in ("code", "math", "table", "list")
        if kind == "paragraph" and not leads_in:
            end = text.rstrip()[-1]
            assert end in ".:;!?)`*_]>}\"'|$" or text.rstrip().endswith("```"), \
                f"{page}.md: a paragraph stops mid-sentence: ...{text.rstrip()[-70:]!r}"


def test_the_readme_opens_with_its_two_commands():
    """Issue 41: the README under 120 lines, its two copy-paste commands (set up and run the main
    job; set up and run the tests) before line 15, and no other set-up command."""
    lines = (DOCS.parent / "README.md").read_text().splitlines()
    assert len(lines) < 120
    setup = [k for k, line in enumerate(lines, start=1) if line.startswith("bash scripts/setup.sh")]
    assert [lines[k - 1] for k in setup] == ["bash scripts/setup.sh && .venv/bin/fetorsion run",
                                             "bash scripts/setup.sh && .venv/bin/python -m pytest -q"]
    assert max(setup) < 15
