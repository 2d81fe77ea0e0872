"""The claims ledger's computations that belong to no analysis of their own, one module a chapter
(chapter1-chapter4, chapter6, chapter7, appendices), with the launch several share (launches).

Each function turns a remark of the text into a number, its docstring saying how. SI units
inside; arguments name their units. Flights come from the cached engines of the analyses the
modules import (:mod:`~harp_analysis.analyses.scenarios`,
:mod:`~harp_analysis.analyses.comparisons`, :mod:`~harp_analysis.analyses.effort`), so the
ledger and the notebooks share one run; a module that flies its own says which.
"""
