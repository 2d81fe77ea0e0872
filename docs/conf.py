"""Sphinx configuration of the harp-analysis site (``make docs``; issue 28).

The source tree Sphinx reads is assembled by ``python -m harp_analysis.reporting.site sources``
in ``build/docs/source`` (this folder's pages, the generated ones and the notebooks, run once
and cached); this folder holds the configuration, the templates and the static files, read
from here (``sphinx-build -c docs``). The notebooks arrive with their outputs or without, so
myst-nb never runs them (``nb_execution_mode = "off"``).

Every warning fails the build (``-W``), broken cross-references included (``-n``, nitpicky):
the package's docstrings cite each other with Sphinx roles to full names
(:func:`~harp_analysis.engines.mks.for_launch`), or a suffix only the one object's name ends
with, or a name of the citing module or class; a private name, an instance attribute without a
"#:" comment or a type variable is a literal, never a link. Sphinx's own Python domain resolves
them all. Third-party types in signatures (numpy, pandas, ...) cannot resolve offline, with no
inventory to fetch: they are ignored by name below, and nothing of the package's own is.
"""

from __future__ import annotations

import datetime
import importlib
import inspect
import re
import typing
from pathlib import Path

import harp_analysis

project = "harp-analysis"
author = "the harp-analysis developers"
copyright = f"{datetime.date.today().year}, {author}"
version = release = harp_analysis.__version__

extensions = [
    "myst_nb",  # the notebooks and the Markdown pages (it brings myst_parser)
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",  # MathJax 3 copied into _static/mathjax: no CDN
]

# absolute: autosummary looks for its templates from the source tree, which is elsewhere
templates_path = [str(Path(__file__).resolve().parent / "_templates")]
html_static_path = ["_static"]
exclude_patterns = ["_build", "**.ipynb_checkpoints", "_generated", "_root"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"

# --- the notebooks: already run (or deliberately not) by harp_analysis.reporting.site -----------
nb_execution_mode = "off"
nb_merge_streams = True
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist", "attrs_inline", "substitution"]
myst_substitutions = {"version": version}
myst_heading_anchors = 3
myst_dmath_double_inline = True

# MathJax from the site itself (sphinx-mathjax-offline copies it into _static/mathjax)
mathjax_path = "mathjax/tex-chtml.js"

# --- the API reference, generated from the package tree (autosummary, recursive) -------------
autosummary_generate = True
# Every public member a module defines, whether its __all__ lists it or not (docstrings cite
# constants that __all__ leaves out), and none it imports. autodoc documents a constant only
# by its "#:" comment; the module template lists the others (_undocumented_constants).
autosummary_ignore_module_all = True
autodoc_default_options = {
    "members": True,
    "undoc-members": True,
    "ignore-module-all": True,
    # what a class inherits from the package's own (private) bases, not from Python's
    "inherited-members": "object,tuple,dict,list,Exception,BaseException,Warning,UserWarning,"
    "RuntimeWarning,ValueError,Enum,IntEnum,float,int,str",
}


def _undocumented_constants() -> dict[str, list[str]]:
    """Per module of the package, the public constants it assigns (not imports) without a
    "#:" comment, in source order: the module template documents them by name and value."""
    import ast
    import pkgutil

    from sphinx.pycode import ModuleAnalyzer

    found = {}
    for info in pkgutil.walk_packages(harp_analysis.__path__, "harp_analysis."):
        module = importlib.import_module(info.name)
        documented = {name for _, name in ModuleAnalyzer.for_module(info.name).find_attr_docs()}
        names = []
        for statement in ast.parse(inspect.getsource(module)).body:
            targets = (
                statement.targets if isinstance(statement, ast.Assign)
                else [statement.target] if isinstance(statement, ast.AnnAssign) else []
            )  # fmt: skip
            for node in (n for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)):
                value = getattr(module, node.id, None)
                if not (
                    node.id.startswith("_")
                    or node.id in documented
                    or node.id in names
                    or callable(value)
                    or inspect.ismodule(value)
                    or isinstance(value, typing.TypeVar | typing.ParamSpec)
                ):
                    names.append(node.id)
        found[info.name] = names
    return found


autosummary_context = {"undocumented_constants": _undocumented_constants()}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True
python_use_unqualified_type_names = True
add_module_names = False

# --- every warning is an error; cross-references are checked ---------------------------------
nitpicky = True
_THIRD_PARTY = (
    "np", "numpy", "npt", "numpy.typing", "pd", "pandas", "scipy", "numba", "matplotlib",
    "mpl", "plt", "Figure", "Axes", "distributed", "dask", "ipywidgets", "widgets", "tomllib",
    "collections", "collections.abc", "typing", "typing_extensions", "concurrent", "pathlib",
    "enum", "dataclasses", "functools", "os", "re", "types", "numbers", "datetime", "warnings",
    "contextlib", "SALib", "tqdm", "filelock", "nbformat", "nbclient", "subprocess",
    "importlib",
)  # fmt: skip
_BUILTINS = (
    "int", "float", "complex", "bool", "str", "bytes", "object", "None", "type", "list",
    "tuple", "dict", "set", "frozenset", "Callable", "Iterable", "Iterator", "Sequence",
    "Mapping", "Generator", "Any", "Path", "ArrayLike", "NDArray", "DataFrame", "Series",
    "ndarray", "Exception", "ValueError", "TypeError", "RuntimeError", "UserWarning",
    "Warning", "NamedTuple", "Enum", "P", "R", "T", "Literal", "Self", "ParamSpec",
    "TypeVar", "Client", "Future", "Lock", "ModuleType",
    "optional", "array", "array_like", "sequence",  # numpy-style "float or array, optional"
)  # fmt: skip
nitpick_ignore_regex = [
    (
        r"py:(class|obj|data|func|meth|attr|exc|mod)",
        rf"({'|'.join(map(re.escape, _THIRD_PARTY))})\..*",
    ),
    (r"py:(class|obj|data|exc)", rf"({'|'.join(map(re.escape, _BUILTINS))})"),
    # a dataclass whose annotations autodoc prints as the strings they are ('tuple[str, ...]')
    (r"py:class", r"'.*"),
    # a private class a public signature names (mlt.SEGMENT_LOOP, _march, returns a _Flight)
    (r"py:class", r"harp_analysis\.[\w.]*\._\w+"),
]


def _type_variables() -> list[tuple[str, str]]:
    """The package's type variables as its signatures name them (``sweeps.Item``): autodoc
    documents none, so they are no broken references."""
    import pkgutil

    return [
        ("py:class", f"{info.name}.{name}")
        for info in pkgutil.walk_packages(harp_analysis.__path__, "harp_analysis.")
        for name, value in vars(importlib.import_module(info.name)).items()
        if isinstance(value, typing.TypeVar | typing.ParamSpec)
    ]


nitpick_ignore = _type_variables()

# --- the page ------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"harp-analysis {version}"
html_css_files = ["site.css"]
html_js_files = ["ledger.js"]
html_last_updated_fmt = None
html_show_sourcelink = False
html_copy_source = False
html_theme_options = {
    # nothing fetched from outside: no icon links, no analytics, no version switcher
    "icon_links": [],
    "navbar_end": ["theme-switcher", "navbar-icon-links"],
    "show_version_warning_banner": False,
    "navigation_with_keys": False,
    "footer_start": ["copyright"],
    "footer_end": ["last-updated"],
    "secondary_sidebar_items": ["page-toc"],
    "header_links_before_dropdown": 8,
}
html_context = {"default_mode": "light"}
html_sidebars = {"ledger": [], "index": []}  # the ledger's wide table gets the page's width


# --- numpy-style sections ------------------------------------------------------------------


_LITERAL = re.compile(r"(``.*?``|:[a-z:]+:`[^`]*`)")


def _plain_bars(app, what, name, obj, options, lines):
    """The docstrings write |x| for a magnitude (|r| - R, |Vrel|), never a reST substitution:
    every bar outside a literal or a role is escaped."""
    for i, line in enumerate(lines):
        if "|" in line:
            parts = _LITERAL.split(line)
            lines[i] = "".join(
                part if n % 2 else part.replace("|", "\\|") for n, part in enumerate(parts)
            )


def _skip_third_party(app, what, name, obj, skip, options):
    """A function or class a module imports from another package (scipy's ``bootstrap``) is
    never documented there; skipped before autodoc formats its signature."""
    defined_in = getattr(obj, "__module__", None)
    if what == "module" and isinstance(defined_in, str) and (callable(obj) or inspect.isclass(obj)):
        if not defined_in.startswith("harp_analysis"):
            return True
    return None


def _no_type_docstring(app, what, name, obj, options, lines):
    """A constant without a "#:" comment has no docstring of its own: never show its type's
    (a dict's "dict() -> new empty dictionary")."""
    if what in ("data", "attribute") and lines:
        own = type(obj).__doc__
        if isinstance(own, str) and "\n".join(lines).strip() == inspect.cleandoc(own).strip():
            lines[:] = []


def _numpy_sections(app, what, name, obj, options, lines):
    """Napoleon's numpy-style sections (Parameters, Returns, ...) in the docstrings of functions,
    methods and classes only: on a module attribute Napoleon would read the text before a colon
    of a ``#:`` comment ("The explorer's notebook: a Voila app") as the attribute's type."""
    if what in ("function", "method", "class", "exception"):
        from sphinx.ext.napoleon import Config
        from sphinx.ext.napoleon.docstring import NumpyDocstring

        config = Config(napoleon_google_docstring=False, napoleon_use_rtype=False)
        lines[:] = NumpyDocstring(lines, config, app, what, name, obj, options).lines()


def _api_names(app, doctree):
    """An API page's title is its module's dotted name, up to 54 characters, wider than the
    sidebar and than the heading's line: the navigation and the breadcrumbs show its last part
    ("verification" under "fire_control", where the tree says the rest), and the heading the
    whole name with a line break allowed after each dot (<wbr>), so that neither is ever broken
    mid-word. Runs after Sphinx has collected the page's title and contents."""
    from docutils import nodes

    docname = app.env.docname
    module = docname.removeprefix("api/")
    if not docname.startswith("api/harp_analysis."):
        return
    short = module.rpartition(".")[2]
    app.env.titles[docname] = nodes.title("", short)
    entry = next(app.env.tocs[docname].findall(nodes.reference))
    entry.children[:] = [nodes.Text(short)]
    heading = next(doctree.findall(nodes.title))
    parts = [nodes.Text(part + ".") for part in module.split(".")]
    parts[-1] = nodes.Text(short)
    wbr = nodes.raw("", "<wbr>", format="html")
    heading.children[:] = [node for part in parts for node in (part, wbr.deepcopy())][:-1]


def setup(app):
    app.connect("autodoc-process-docstring", _no_type_docstring, priority=300)
    app.connect("autodoc-process-docstring", _plain_bars, priority=400)
    app.connect("autodoc-process-docstring", _numpy_sections)
    app.connect("autodoc-skip-member", _skip_third_party)
    app.connect("doctree-read", _api_names, priority=900)  # after the title and toc collectors
