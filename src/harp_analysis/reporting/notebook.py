"""What a chapter notebook's reader sees of the models' validity warnings.

A model used outside its validity warns (a
:class:`~harp_analysis.foundation.validation.ModelValidityWarning`), and a notebook shows it:
never silenced, but shown once, as a sentence. Python's own display
of a warning is the file and line of the package that warned (a path of the machine that ran
the notebook) and the line of code, and it repeats a warning whenever a filter changed in
between (the engines change them to keep quiet what they judge themselves), so that the same
warning would be printed under every cell that flies the same launch.
"""

from __future__ import annotations

import sys
import warnings
from typing import TextIO

from ..foundation.validation import ModelValidityWarning

__all__ = ["show_validity_warnings", "sentence"]


def sentence(message: Warning | str) -> str:
    """A validity warning's ``message`` as the sentence a reader sees: "Model validity: MKS
    beta = 0.275 > 0.25: the text finds the solution inaccurate for such high-drag projectiles
    (Ch. 4 B)." (its line breaks folded, a full stop added).

    Parameters
    ----------
    message : Warning or str
        The warning, or its text.

    Returns
    -------
    str
        The sentence, one line without its line break.
    """
    text = " ".join(str(message).split()).rstrip(".")
    return f"Model validity: {text}."


class _Once:
    """:func:`warnings.showwarning` while a notebook runs: each distinct validity warning written
    once as its :func:`sentence`, any other warning by Python's own display (``others``)."""

    def __init__(self, others) -> None:
        self.others = others
        self.shown: set[str] = set()

    def __call__(
        self,
        message: Warning | str,
        category: type[Warning],
        filename: str,
        lineno: int,
        file: TextIO | None = None,
        line: str | None = None,
    ) -> None:
        if not issubclass(category, ModelValidityWarning):
            self.others(message, category, filename, lineno, file, line)
            return
        said = sentence(message)
        if said not in self.shown:
            self.shown.add(said)
            print(said, file=file or sys.stderr)


def show_validity_warnings() -> None:
    """Show each distinct :class:`~harp_analysis.foundation.validation.ModelValidityWarning`
    from now on once, as its :func:`sentence`, without the paths and code lines of Python's own
    display; other warnings are shown as Python shows them. A chapter notebook calls it once,
    in its imports cell; calling it again starts the count of warnings shown afresh. It sets
    the process's filter for validity warnings to "always" (the count is its own) and replaces
    :func:`warnings.showwarning`.
    """
    current = warnings.showwarning
    others = current.others if isinstance(current, _Once) else current
    warnings.simplefilter("always", ModelValidityWarning)
    warnings.showwarning = _Once(others)
