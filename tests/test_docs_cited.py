"""Docstrings and comments cite the design in ``docs/``, and every page they cite is there.

A clone of the repository is all a reader has: a citation of a file outside it (the
planning folder the project started from) or of a page that was renamed sends them
nowhere.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CITED = re.compile(r"docs/([\w./-]+\.md)")
OUTSIDE = re.compile(r"(?:\.\./|/work/)?shared/(?:spec|reference|DESIGN|STYLE)")
LINK = re.compile(r"\]\(([\w./-]+\.md)(?:#[\w-]*)?\)")


def _sources() -> list[Path]:
    here = Path(__file__).resolve()
    return [path for folder in ("torsal", "tools", "tests") for path in sorted((ROOT / folder).rglob("*.py"))
            if path != here]


def test_every_cited_docs_page_exists():
    missing = {
        f"{path.relative_to(ROOT)}: docs/{page}"
        for path in _sources()
        for page in CITED.findall(path.read_text(encoding="utf-8"))
        if not (ROOT / "docs" / page).is_file()
    }
    assert not missing, sorted(missing)


def test_nothing_cites_a_file_outside_the_repository():
    outside = [str(path.relative_to(ROOT)) for path in _sources()
               if OUTSIDE.search(path.read_text(encoding="utf-8"))]
    assert not outside, outside


def test_links_between_docs_pages_resolve():
    pages = sorted((ROOT / "docs").glob("*.md"))
    assert {"architecture.md", "data-trees.md", "graph-format.md", "geometry.md"} <= {p.name for p in pages}
    broken = {f"{page.name} -> {link}" for page in pages for link in LINK.findall(page.read_text("utf-8"))
              if not (page.parent / link).is_file()}
    assert not broken, sorted(broken)


def test_the_checker_sees_a_missing_page_and_an_outside_citation():
    text = 'see ``docs/no-such-page.md`` and ``shared/spec/data-trees.md``'
    assert CITED.findall(text) == ["no-such-page.md"] and not (ROOT / "docs" / "no-such-page.md").exists()
    assert OUTSIDE.search(text)
