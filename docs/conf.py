"""Sphinx configuration of the harp-analysis site (``make docs``; issue 28).

The source tree Sphinx reads is assembled by ``python -m harp_analysis.reporting.site sources``
in ``build/docs/source`` (this folder's pages, the generated ones and the notebooks, run once
and cached); this folder holds the configuration, the templates and the static files, read
from here (``sphinx-build -c docs``). The notebooks arrive with their outputs or without, so
myst-nb never runs them (``nb_execution_mode = "off"``).

Every warning fails the build (``-W``), broken cross-references included (``-n``, nitpicky):
the package's docstrings cite each other with Sphinx roles, fully qualified
(:func:`harp_analysis.engines.mks.for_launch`), by a dotted suffix (:func:`.atmosphere.day_air`,
:mod:`.eci`), or by the name the citing module imports (:func:`case`, ``apogees.drag_area_m2``).
The Python domain searches for a suffix; ``setup`` below adds the rest (_resolve), and picks the
nearest of several objects a suffix names (_nearest: ``.atmosphere`` is the model, not the
figures of it), so a new module that shares a name with another breaks no reference. Third-party
types in signatures (numpy, pandas, ...) cannot resolve offline, with no inventory to fetch:
they are ignored by name below, and nothing of the package's own is.
"""

from __future__ import annotations

import datetime
import importlib
import inspect
import os
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
    "optional", "array_like", "sequence",  # numpy-style "float, optional", "sequence of int"
)  # fmt: skip
nitpick_ignore_regex = [
    (
        r"py:(class|obj|data|func|meth|attr|exc|mod)",
        rf"({'|'.join(map(re.escape, _THIRD_PARTY))})\..*",
    ),
    (r"py:(class|obj|data|exc)", rf"({'|'.join(map(re.escape, _BUILTINS))})"),
    # a dataclass whose annotations autodoc prints as the strings they are ('tuple[str, ...]')
    (r"py:class", r"'.*"),
]

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


# --- numpy-style sections, and references by a dotted suffix ---------------------------------


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


def _instance_attribute(node, target: str) -> bool:
    """Whether ``target`` is an attribute that the class of the reference (or, from a module's
    summary table, the one class of its module) sets on its instances (``self.kernel = ...``):
    it exists, but autodoc documents such an attribute only by a "#:" comment, so it is shown
    without a link."""
    module_name, owner = node.get("py:module"), node.get("py:class")
    if not module_name:
        return False
    try:
        module = importlib.import_module(module_name)
    except ImportError:
        return False
    if owner:
        candidates = [module]
        for part in owner.split("."):
            candidates = [getattr(candidates[0], part, None)]
    else:
        candidates = [
            value
            for value in vars(module).values()
            if inspect.isclass(value) and value.__module__ == module_name
        ]
    setting = re.compile(rf"\bself\.{re.escape(target)}\s*(:[^=]*)?=")
    found = []
    for cls in candidates:
        try:
            found += [cls] if setting.search(inspect.getsource(cls)) else []
        except (OSError, TypeError):
            pass
    return len(found) == 1


def _in_namespace(node, target: str) -> str | None:
    """The full name of ``target`` as the module of the reference sees it: a name it imports
    (``case`` in a module that did ``from ..comparisons import case``) or an attribute of a
    module it imports (``apogees.speed_of_sound``), followed to where it is defined."""
    module_name = node.get("py:module")
    if not module_name:
        return None
    try:
        value = importlib.import_module(module_name)
    except ImportError:
        return None
    home, rest = module_name, []
    for part in target.split("."):
        if not hasattr(value, part):
            return None
        value = getattr(value, part)
        if inspect.ismodule(value):
            home, rest = value.__name__, []
        else:
            rest.append(part)
    if inspect.ismodule(value):
        return value.__name__
    defined_in = getattr(value, "__module__", None)
    qualified = getattr(value, "__qualname__", None)
    if isinstance(defined_in, str) and isinstance(qualified, str) and len(rest) == 1:
        return f"{defined_in}.{qualified}"
    return ".".join([home, *rest])


def _through_a_package(domain, target: str) -> str | None:
    """The full name of ``target`` read through a module named by a unique dotted suffix: a
    name a package re-exports (``fire_control.verify_with_3dof``, defined in
    ``fire_control.verification``), followed to where it is defined."""
    parts = target.split(".")
    for cut in range(len(parts) - 1, 0, -1):
        head = ".".join(parts[:cut])
        modules = [m for m in domain.modules if m == head or m.endswith("." + head)]
        found = set()
        for module in modules:
            first = getattr(importlib.import_module(module), parts[cut], None)
            owner = getattr(first, "__module__", None)
            if first is None or inspect.ismodule(first):
                continue
            defined = inspect.isclass(first) or inspect.isroutine(first)
            if not (defined and isinstance(owner, str)):
                # a constant: the documented one that is the same object
                found |= {
                    name
                    for name in domain.objects
                    if name.endswith("." + parts[cut])
                    and getattr(
                        importlib.import_module(domain.objects[name].docname.split("/")[-1]),
                        parts[cut],
                        None,
                    )
                    is first
                }
                continue
            # a name defined elsewhere and re-exported here, or a member of it
            qualified = ".".join([owner, first.__name__ if inspect.isclass(first) else parts[cut]])
            full = ".".join([qualified, *parts[cut + 1 :]])
            if full in domain.objects:
                found.add(full)
        if len(found) == 1:
            return found.pop()
    return None


def _resolve(app, env, node, contnode):
    """A Python reference the domain's own lookup did not find: the name as the citing module
    sees it (_in_namespace), or read through a package that re-exports it
    (_through_a_package); a private name, an instance attribute or a type variable shown
    unlinked; else the package object whose full name ends with it (``Launch`` in a signature,
    ``mks.ModifiedKeplerSolution``), the nearest of several (_nearest). An unknown or still
    ambiguous name is left to Sphinx's warning."""
    if node.get("refdomain") != "py":
        return None
    from sphinx.util.nodes import make_refnode

    target = node["reftarget"].lstrip(".~")
    domain = env.domains["py"]
    seen = _in_namespace(node, target)
    if seen not in domain.objects:
        seen = _through_a_package(domain, target)
    if seen in domain.objects:
        entry = domain.objects[seen]
        return make_refnode(
            app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, seen
        )
    if target.rpartition(".")[2].startswith("_"):
        return contnode  # a private name, shown but never documented, so never linked
    if node.get("reftype") == "attr" and _instance_attribute(node, target):
        return contnode
    if target.rpartition(".")[0].startswith("harp_analysis."):  # a type variable's name
        module, _, attribute = target.rpartition(".")
        try:
            value = getattr(importlib.import_module(module), attribute, None)
        except ImportError:
            value = None
        if isinstance(value, typing.TypeVar | typing.ParamSpec):
            return contnode
    matches = [
        name
        # the package's objects only: a numpy or pandas name never resolves to one of them
        for name in domain.objects
        if name.startswith("harp_analysis") and (name == target or name.endswith("." + target))
    ]
    if len(matches) > 1 and node.get("py:module"):
        matches = [name for name, _ in _nearest([(m, None) for m in matches], node["py:module"])]
    if len(matches) != 1:
        return None
    entry = domain.objects[matches[0]]
    return make_refnode(
        app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, matches[0]
    )


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


def _layer(name: str) -> int:
    """The layer of a module of the package, lowest first (pyproject's import-linter layers)."""
    for depth, layer in enumerate(("foundation", "models", "engines", "analyses", "reporting")):
        if name.startswith(f"harp_analysis.{layer}"):
            return depth
    return 5


def _nearest(matches: list, module: str) -> list:
    """Of several objects a dotted suffix names (``.atmosphere``: the model and the figures of
    it), the one a docstring of ``module`` means: not the module itself, then the one sharing
    the longest package path with it, then the one in the lowest layer (a module cites those it
    builds on); all of them if that leaves more than one, and Sphinx warns."""
    others = [m for m in matches if m[0] != module]
    if len(others) <= 1:
        return others or matches

    def shared(name: str) -> int:
        return len(os.path.commonprefix([name.split("."), module.split(".")]))

    best = max(shared(m[0]) for m in others)
    others = [m for m in others if shared(m[0]) == best]
    lowest = min(_layer(m[0]) for m in others)
    others = [m for m in others if _layer(m[0]) == lowest]
    return others if len(others) == 1 else matches


def setup(app):
    from sphinx.domains.python import PythonDomain

    class PackagePython(PythonDomain):
        """The Python domain, choosing among several objects a dotted suffix names (_nearest)."""

        def find_obj(self, env, modname, classname, name, type, searchmode=0):
            matches = super().find_obj(env, modname, classname, name, type, searchmode)
            if len(matches) > 1 and modname and modname.startswith("harp_analysis"):
                matches = _nearest(matches, modname)
            return matches

    app.add_domain(PackagePython, override=True)
    app.connect("autodoc-process-docstring", _no_type_docstring, priority=300)
    app.connect("autodoc-process-docstring", _plain_bars, priority=400)
    app.connect("autodoc-process-docstring", _numpy_sections)
    app.connect("autodoc-skip-member", _skip_third_party)
    app.connect("missing-reference", _resolve)
    app.connect("doctree-read", _api_names, priority=900)  # after the title and toc collectors
