"""The check of the built documentation site (``make docs``' last step, issue 28): every internal
link, anchor and image of its HTML pages is there, and nothing is loaded from outside it.

``python -m harp_analysis.reporting.site check build/docs/html`` runs :func:`check_site`. Links
out of the site (``http``, ``mailto``) are allowed but never followed; a resource from outside
(a CDN, a web font) is refused, so that the site works offline.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

__all__ = ["check_site", "html_pages"]

#: The attribute of each tag that loads a resource into the page.
_RESOURCE_ATTRIBUTE = {
    **dict.fromkeys(("img", "script", "iframe", "source", "embed", "audio", "video"), "src"),
    "link": "href",
    "object": "data",
}
_CSS_URL = re.compile(r"""url\(\s*['"]?([^'")]+)['"]?\s*\)|@import\s+['"]([^'"]+)['"]""")


class _Page(HTMLParser):
    """The ids, links and resources of one HTML page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.links: list[str] = []
        self.resources: list[tuple[str, str]] = []  # (tag, url)

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = {name: value for name, value in attrs if value is not None}
        named = ("id", "name") if tag == "a" else ("id",)  # an anchor's name is a target too
        self.ids.update(values[name] for name in named if name in values)
        if tag == "a" and "href" in values:
            self.links.append(values["href"])
        self.resources += [(tag, url) for url in _loaded(tag, values)]


def _loaded(tag: str, values: dict[str, str]) -> list[str]:
    """The urls an element ``tag`` with attributes ``values`` loads: its
    :data:`_RESOURCE_ATTRIBUTE`, then each candidate of its ``srcset`` ("a.png 1x, b.png 2x")."""
    loads = _RESOURCE_ATTRIBUTE.get(tag, "")
    urls = [values[loads]] if loads in values else []
    srcset = values.get("srcset")
    return urls + ([part.split()[0] for part in srcset.split(",")] if srcset else [])


def _external(url: str) -> bool:
    parts = urlsplit(url)
    return bool(parts.scheme and parts.scheme not in ("data", "file")) or url.startswith("//")


def _resolve(base: Path, url: str) -> tuple[Path, str]:
    """The file ``url``, seen from page ``base``, reaches (a folder's index.html), and its
    fragment."""
    parts = urlsplit(url)
    target = (base.parent / unquote(parts.path)).resolve() if parts.path else base
    if target.is_dir():
        target = target / "index.html"
    return target, unquote(parts.fragment)


def html_pages(site: Path) -> Iterator[Path]:
    """The HTML pages of the built site ``site``, but the theme's templates Sphinx copies as
    they are into ``_static`` (webpack-macros.html), which are no pages."""
    for path in sorted(site.rglob("*.html")):
        if path.relative_to(site).parts[0] != "_static":
            yield path


def _link_problems(name: str, path: Path, page: _Page, pages: dict[Path, _Page]) -> list[str]:
    """Where a link of ``page`` (``path``, named ``name``) to the site reaches no file, or no
    element with the id its fragment names."""
    problems = []
    for url in page.links:
        if _external(url) or url.startswith(("mailto:", "javascript:")):
            continue
        target, fragment = _resolve(path, url)
        if not target.is_file():
            problems.append(f"{name}: link {url!r} reaches no file")
        elif fragment and target.suffix == ".html" and fragment not in pages[target].ids:
            problems.append(f"{name}: link {url!r} reaches no element id={fragment!r}")
    return problems


def _resource_problems(name: str, path: Path, page: _Page) -> list[str]:
    """Where ``page`` (``path``, named ``name``) loads something from outside the site, or a
    file of the site that is missing."""
    problems = []
    for tag, url in page.resources:
        if _external(url):
            problems.append(f"{name}: <{tag}> loads {url!r} from outside the site")
        elif not url.startswith("data:") and not _resolve(path, url)[0].is_file():
            problems.append(f"{name}: <{tag}> {url!r} is missing")
    return problems


def _stylesheet_problems(site: Path) -> list[str]:
    """Where a stylesheet of ``site`` loads something from outside it (``url()``,
    ``@import``), or a file of the site that is missing."""
    problems = []
    for css in sorted(site.rglob("*.css")):
        for match in _CSS_URL.finditer(css.read_text(errors="replace")):
            url = match.group(1) or match.group(2)
            if url.startswith(("data:", "#")):
                continue
            if _external(url):
                problems.append(f"{css.relative_to(site)}: loads {url!r} from outside the site")
            elif not (css.parent / unquote(urlsplit(url).path)).is_file():
                problems.append(f"{css.relative_to(site)}: {url!r} is missing")
    return problems


def check_site(site: Path) -> list[str]:
    """What is wrong with the built site in ``site``: every link of every page to another page
    of the site must reach an existing file and, with a fragment, an element with that id; every
    image, script and stylesheet must be there; no page or stylesheet may load anything from
    outside (a CDN, a web font), so that the site works offline. Links out of the site (``http``,
    ``mailto``) are allowed but never followed. Empty when all is well."""
    site = Path(site).resolve()
    pages: dict[Path, _Page] = {}
    for path in html_pages(site):
        parser = _Page()
        parser.feed(path.read_text(errors="replace"))
        pages[path.resolve()] = parser
    if not pages:
        return [f"{site}: no HTML page"]
    problems = []
    for path, page in pages.items():
        name = path.relative_to(site).as_posix()
        problems += _link_problems(name, path, page, pages)
        problems += _resource_problems(name, path, page)
    return problems + _stylesheet_problems(site)
